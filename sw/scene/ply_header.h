// The PLY header: format, elements, properties, and what kdrt takes from
// each property. Used by ply_reader.cpp only; a file of its own so that the
// header rules stay apart from the data walk.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "scene/text_fields.h"

namespace kdrt {

enum class PlyType { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

size_t PlySize(PlyType t);
bool IsFloatType(PlyType t);

// What kdrt takes from a property; everything else is checked and skipped.
enum class PlyRole { kSkip, kX, kY, kZ, kFaceIndices };

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::kFloat32;  // item type for lists
  bool is_list = false;
  PlyType count_type = PlyType::kUint8;
  PlyRole role = PlyRole::kSkip;
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> props;
  int line = 0;
};

enum class PlyFormat { kAscii, kBinaryLittle, kBinaryBig };

struct PlyHeader {
  PlyFormat format = PlyFormat::kAscii;
  std::vector<PlyElement> elements;
};

// Reads and checks the header of `bytes` (the whole file) and leaves `lines`
// on the first data byte. Throws InputError with the header line. Element
// counts are checked against the data size, so they are safe to reserve.
PlyHeader ReadPlyHeader(const std::string& path, const std::string& bytes, LineCursor* lines);

}  // namespace kdrt
