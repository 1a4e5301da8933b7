#include "core/strategies/skin_audit.h"

#include <algorithm>

#include "core/assert.h"
#include "core/tuning.h"

namespace sap_broadphase {
namespace {

enum class FrameKind { kPlain, kWithSkin, kNeither };

// A plain frame is a sweep or kernel of unchanged ids without a skin (a first frame or one of
// new ids also loads them: not the cost a skin would replace); a skin's frame is answered by
// kept candidates or grows its boxes for them.
FrameKind kindOf(const FramePlan& inPlan, const FrameDelta& inDelta) {
  if (inPlan.path == FramePath::kSkin) return FrameKind::kWithSkin;
  if (!findsAllPairs(inPlan.path)) return FrameKind::kNeither;
  if (inPlan.sweep_skin > 0.0) return FrameKind::kWithSkin;
  return inDelta.relation == FrameRelation::kSameIds ? FrameKind::kPlain : FrameKind::kNeither;
}

}  // namespace

void SkinAudit::record(const FramePlan& inPlan, const FrameDelta& inDelta, std::size_t inBoxes,
                       double inMilliseconds) {
  if (inBoxes == 0) return;
  const double ns_per_box = inMilliseconds * 1e6 / static_cast<double>(inBoxes);
  const FrameKind kind = kindOf(inPlan, inDelta);
  // The grown sweep that starts a skin after frames without one is its entry, paid once for
  // the many frames it answers: weighed in a window of 16 frames, it made the skin look dearer
  // than plain frames where it pays (2^17, d = 0.05: probations in 4 runs of 6). A frame that
  // finds its pairs without a skin ends a skin; a reused frame leaves it as it was.
  const bool entry = kind == FrameKind::kWithSkin && !skin_live_;
  if (inPlan.path == FramePath::kSkin || findsAllPairs(inPlan.path))
    skin_live_ = kind == FrameKind::kWithSkin;
  switch (kind) {
    case FrameKind::kPlain:
      plain_ns_per_box_ =
          plain_ns_per_box_ > 0.0
              ? plain_ns_per_box_ + tuning::kCostSmoothing * (ns_per_box - plain_ns_per_box_)
              : ns_per_box;
      probation_left_ = std::max(0, probation_left_ - 1);
      break;
    case FrameKind::kWithSkin:
      SAP_ASSERT(probation_left_ == 0, "a skin's frame during the skin's probation");
      if (entry && inPlan.path != FramePath::kSkin) break;
      skin_ns_per_box_sum_ += ns_per_box;
      if (++skin_frames_ == tuning::kSkinAuditFrames) judgeSkin();
      break;
    case FrameKind::kNeither:
      break;
  }
}

// At the end of a window: the skin keeps its place only if its frames cost less than plain
// ones; if not, a probation, doubled for each failure in a row.
void SkinAudit::judgeSkin() {
  const double skin_mean = skin_ns_per_box_sum_ / skin_frames_;
  skin_ns_per_box_sum_ = 0.0;
  skin_frames_ = 0;
  if (skin_mean < plain_ns_per_box_) {
    next_probation_ = tuning::kSkinAuditFirstProbation;
    return;
  }
  probation_left_ = next_probation_;
  next_probation_ = std::min(2 * next_probation_, tuning::kSkinAuditLongestProbation);
}

}  // namespace sap_broadphase
