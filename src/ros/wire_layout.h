// WireLayout: a ROS 1 message type read from its full definition, to check serialized bytes
// before anything is allocated for them. roscpp's deserializers believe every length prefix
// (a string's, an array's) and allocate what it claims before reading the bytes, so one message
// of a few bytes claiming 10^9 elements throws std::bad_alloc or holds gigabytes. A message that
// passes check() has no prefix larger than the bytes that follow it, so deserializing it
// allocates at most a constant times its size on the wire (the largest ratio of an element's
// size in memory to its smallest size on the wire: a std::string of 32 bytes for an empty
// string's 4).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace sap_broadphase {

class WireLayout {
 public:
  /// Reads inDefinition, the full text of type inType as gencpp writes it (message_traits::
  /// Definition): the type's own fields, then each type it uses after a line of '=' and
  /// "MSG: pkg/Type". Throws std::invalid_argument on a definition it cannot read (a type it
  /// uses is missing): a bug of the node, never of the input.
  WireLayout(const std::string& inType, const std::string& inDefinition);

  /// Walks inData (inSize bytes) field by field. Returns the refusal, naming the field and
  /// what its prefix claims against the bytes left, or nothing when the bytes are exactly one
  /// message of the type (none short, none left over).
  std::optional<std::string> check(const uint8_t* inData, std::size_t inSize) const;

  const std::string& typeName() const { return type_name_; }

 private:
  static constexpr int kString = -1;  // a field's type: a string
  static constexpr int kNoArray = -1;
  static constexpr int kVariableArray = -2;
  struct Field {
    std::string name;
    int type = 0;          // kString, a builtin's negative size -(2 + bytes), or a type index
    int array = kNoArray;  // kNoArray, kVariableArray, or the fixed length
  };
  struct Type {
    std::string name;
    std::vector<Field> fields;
    std::size_t fixed_size = 0;  // bytes of every value, when fixed
    bool fixed = true;
    std::size_t min_size = 0;  // fewest bytes of a value (4 per string or variable array)
  };
  /// Index of type inName (resolved in package inPackage), parsed from the sections of the
  /// definition; builtin types are negative codes.
  int resolve(const std::string& inName, const std::string& inPackage,
              const std::vector<std::pair<std::string, std::string>>& inSections);
  int parseType(const std::string& inName,
                const std::vector<std::pair<std::string, std::string>>& inSections);
  /// Walks a value of type inType from ioOffset; false with outError on a lying prefix or a
  /// short message.
  bool walk(int inType, const uint8_t* inData, std::size_t inSize, std::size_t& ioOffset,
            std::string& outError) const;
  bool walkField(const Field& inField, const uint8_t* inData, std::size_t inSize,
                 std::size_t& ioOffset, std::string& outError) const;
  std::size_t valueMinSize(int inType) const;
  std::optional<std::size_t> valueFixedSize(int inType) const;

  std::string type_name_;
  std::vector<Type> types_;
  int root_ = 0;
};

}  // namespace sap_broadphase
