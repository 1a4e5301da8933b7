// Names of the report's enumerations (frame_report.h).
#include "sap_broadphase/core/frame_report.h"

namespace sap_broadphase {

const char* skinChoiceName(SkinChoice inChoice) {
  switch (inChoice) {
    case SkinChoice::kOff:
      return "off";
    case SkinChoice::kFixed:
      return "fixed";
    case SkinChoice::kFirstFrame:
      return "first_frame";
    case SkinChoice::kIdsChanged:
      return "ids_changed";
    case SkinChoice::kKept:
      return "kept";
    case SkinChoice::kChosen:
      return "chosen";
    case SkinChoice::kTooFast:
      return "too_fast";
    case SkinChoice::kNotWorthIt:
      return "not_worth_it";
    case SkinChoice::kOverBudget:
      return "over_budget";
  }
  return "unknown";
}

const char* framePathName(FramePath inPath) {
  switch (inPath) {
    case FramePath::kEmpty:
      return "empty";
    case FramePath::kSequential:
      return "sequential";
    case FramePath::kParallel:
      return "parallel";
    case FramePath::kBruteForce:
      return "brute";
    case FramePath::kReused:
      return "reused";
    case FramePath::kSkin:
      return "skin";
    case FramePath::kSmallFrame:
      return "small";
  }
  return "unknown";
}

}  // namespace sap_broadphase
