// Names of the report's enumerations and the text of its fields (frame_report.h).
#include "sap_broadphase/core/frame_report.h"

#include <cstdio>

#include "sap_broadphase/core/config.h"

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

std::string reportValueText(ReportUnit inUnit, double inValue) {
  char text[64];
  std::snprintf(text, sizeof text, inUnit == ReportUnit::kMilliseconds ? "%.3f" : "%.6g", inValue);
  return text;
}

std::string reportValueText(ReportUnit inUnit, std::size_t inValue) {
  return inUnit == ReportUnit::kAxis ? axisName(static_cast<int>(inValue))
                                     : std::to_string(inValue);
}

std::string reportValueText(ReportUnit inUnit, int inValue) {
  return inUnit == ReportUnit::kAxis ? axisName(inValue) : std::to_string(inValue);
}

std::string reportValueText(ReportUnit /*inUnit*/, bool inValue) {
  return inValue ? "true" : "false";
}

std::string reportValueText(ReportUnit /*inUnit*/, FramePath inValue) {
  return framePathName(inValue);
}

std::string reportValueText(ReportUnit /*inUnit*/, SkinChoice inValue) {
  return skinChoiceName(inValue);
}

std::string reportLines(const FrameReport& inReport) {
  std::string lines;
  forEachReportField(inReport, [&](const ReportField& inField, auto inValue) {
    lines += std::string(inField.name) + " " + reportValueText(inField.unit, inValue) + "\n";
  });
  return lines;
}

}  // namespace sap_broadphase
