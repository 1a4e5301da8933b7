// WireLayout: serialized ROS 1 messages checked against their definition.
#include "wire_layout.h"

#include <cstring>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace sap_broadphase {

namespace {

/// Bytes of a builtin fixed-size type, or 0 when inName is none.
std::size_t builtinSize(const std::string& inName) {
  static const std::pair<const char*, std::size_t> kBuiltins[] = {
      {"bool", 1},  {"int8", 1},   {"uint8", 1},   {"byte", 1},   {"char", 1},
      {"int16", 2}, {"uint16", 2}, {"int32", 4},   {"uint32", 4}, {"float32", 4},
      {"int64", 8}, {"uint64", 8}, {"float64", 8}, {"time", 8},   {"duration", 8}};
  for (const auto& [name, size] : kBuiltins)
    if (inName == name) return size;
  return 0;
}

std::string trimmed(const std::string& inText) {
  const auto first = inText.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return inText.substr(first, inText.find_last_not_of(" \t\r") - first + 1);
}

/// The definition cut into (type name, text) sections: the first is inType's own.
std::vector<std::pair<std::string, std::string>> sectionsOf(const std::string& inType,
                                                            const std::string& inDefinition) {
  std::vector<std::pair<std::string, std::string>> sections{{inType, ""}};
  std::istringstream lines(inDefinition);
  std::string line;
  while (std::getline(lines, line)) {
    const std::string text = trimmed(line);
    if (text.size() >= 2 && text.find_first_not_of('=') == std::string::npos) {
      sections.emplace_back("", "");
    } else if (text.rfind("MSG:", 0) == 0 && sections.back().first.empty()) {
      sections.back().first = trimmed(text.substr(4));
    } else {
      sections.back().second += line + "\n";
    }
  }
  return sections;
}

uint32_t readLength(const uint8_t* inData) {
  uint32_t length = 0;
  std::memcpy(&length, inData, sizeof length);  // little-endian, as ROS 1 serializes
  return length;
}

}  // namespace

WireLayout::WireLayout(const std::string& inType, const std::string& inDefinition)
    : type_name_(inType) {
  root_ = parseType(inType, sectionsOf(inType, inDefinition));
}

int WireLayout::resolve(const std::string& inName, const std::string& inPackage,
                        const std::vector<std::pair<std::string, std::string>>& inSections) {
  if (inName == "string") return kString;
  if (const std::size_t size = builtinSize(inName)) return -static_cast<int>(2 + size);
  std::string full = inName;
  if (inName == "Header")
    full = "std_msgs/Header";
  else if (inName.find('/') == std::string::npos)
    full = inPackage + "/" + inName;
  return parseType(full, inSections);
}

int WireLayout::parseType(const std::string& inName,
                          const std::vector<std::pair<std::string, std::string>>& inSections) {
  for (std::size_t k = 0; k < types_.size(); ++k)
    if (types_[k].name == inName) return static_cast<int>(k);
  const std::string* text = nullptr;
  for (const auto& [name, body] : inSections)
    if (name == inName) text = &body;
  if (!text) throw std::invalid_argument("message definition without type " + inName);
  const std::string package = inName.substr(0, inName.find('/'));
  Type type;
  type.name = inName;
  std::istringstream lines(*text);
  std::string line;
  while (std::getline(lines, line)) {
    std::string text_line = trimmed(line.substr(0, line.find('#')));
    if (text_line.empty()) continue;
    std::istringstream words(text_line);
    std::string type_word, name_word;
    words >> type_word >> name_word;
    // A constant ("uint8 ADD=0", "string NAME = text") has no place on the wire.
    if (name_word.empty() || text_line.find('=') != std::string::npos) continue;
    Field field;
    field.name = name_word;
    const auto bracket = type_word.find('[');
    if (bracket != std::string::npos) {
      const std::string length = type_word.substr(bracket + 1, type_word.size() - bracket - 2);
      field.array = length.empty() ? kVariableArray : std::stoi(length);
      type_word = type_word.substr(0, bracket);
    }
    field.type = resolve(type_word, package, inSections);
    type.fields.push_back(std::move(field));
  }
  types_.push_back(std::move(type));
  const int index = static_cast<int>(types_.size() - 1);
  Type& parsed = types_[index];
  for (const Field& field : parsed.fields) {
    const std::size_t count = field.array >= 0 ? static_cast<std::size_t>(field.array) : 1;
    const std::optional<std::size_t> fixed = valueFixedSize(field.type);
    if (field.array == kVariableArray || !fixed) parsed.fixed = false;
    if (fixed) parsed.fixed_size += count * *fixed;
    parsed.min_size += field.array == kVariableArray ? 4 : count * valueMinSize(field.type);
  }
  return index;
}

std::optional<std::size_t> WireLayout::valueFixedSize(int inType) const {
  if (inType == kString) return std::nullopt;
  if (inType < 0) return static_cast<std::size_t>(-inType - 2);
  const Type& type = types_[inType];
  if (!type.fixed) return std::nullopt;
  return type.fixed_size;
}

std::size_t WireLayout::valueMinSize(int inType) const {
  if (inType == kString) return 4;
  if (inType < 0) return static_cast<std::size_t>(-inType - 2);
  return types_[inType].min_size;
}

std::optional<std::string> WireLayout::check(const uint8_t* inData, std::size_t inSize) const {
  std::size_t offset = 0;
  std::string error;
  if (!walk(root_, inData, inSize, offset, error)) return type_name_ + ": " + error;
  if (offset != inSize) {
    return type_name_ + ": " + std::to_string(inSize - offset) +
           " bytes left after the last field: not the layout its MD5 sum promises";
  }
  return std::nullopt;
}

bool WireLayout::walk(int inType, const uint8_t* inData, std::size_t inSize, std::size_t& ioOffset,
                      std::string& outError) const {
  for (const Field& field : types_[inType].fields) {
    if (!walkField(field, inData, inSize, ioOffset, outError)) {
      outError = field.name + (outError[0] == '[' || outError[0] == ':' ? "" : ".") + outError;
      return false;
    }
  }
  return true;
}

bool WireLayout::walkField(const Field& inField, const uint8_t* inData, std::size_t inSize,
                           std::size_t& ioOffset, std::string& outError) const {
  std::size_t count = inField.array >= 0 ? static_cast<std::size_t>(inField.array) : 1;
  const std::size_t element_min = valueMinSize(inField.type);
  if (inField.array == kVariableArray) {
    if (inSize - ioOffset < 4) {
      outError = ": the message ends before its length (" + std::to_string(inSize) + " bytes)";
      return false;
    }
    count = readLength(inData + ioOffset);
    ioOffset += 4;
    // Every element takes at least element_min bytes (an element of no bytes at all counts
    // one, so that an array of empty messages is bounded by the bytes too).
    const std::size_t left = inSize - ioOffset;
    if (count > left / (element_min > 0 ? element_min : 1)) {
      outError = ": claims " + std::to_string(count) + " elements of at least " +
                 std::to_string(element_min) + " bytes, " + std::to_string(left) + " bytes left";
      return false;
    }
  }
  if (const std::optional<std::size_t> fixed = valueFixedSize(inField.type)) {
    if (count * *fixed > inSize - ioOffset) {  // count <= inSize here: no overflow
      outError = ": the message ends early (" + std::to_string(inSize) + " bytes)";
      return false;
    }
    ioOffset += count * *fixed;
    return true;
  }
  for (std::size_t k = 0; k < count; ++k) {
    const std::string index = inField.array == kNoArray ? "" : "[" + std::to_string(k) + "]";
    if (inField.type == kString) {
      const std::size_t left = inSize - ioOffset;
      const uint32_t length = left >= 4 ? readLength(inData + ioOffset) : 0;
      if (left < 4 || length > left - 4) {
        outError = index + (left < 4 ? ": the message ends before a string's length"
                                     : ": a string of " + std::to_string(length) + " bytes, " +
                                           std::to_string(left - 4) + " bytes left");
        return false;
      }
      ioOffset += 4 + length;
    } else if (!walk(inField.type, inData, inSize, ioOffset, outError)) {
      if (!index.empty()) outError = index + "." + outError;
      return false;
    }
  }
  return true;
}

}  // namespace sap_broadphase
