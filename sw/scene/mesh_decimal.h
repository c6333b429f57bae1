// Decimal coordinates in PLY and OFF text. kdrt read these formats through
// assimp 5.2, whose fast_atof is not correctly rounded (about 1% of "%.9g"
// values and a third of "%e" values land one float away from the nearest).
// The readers now compute assimp's value themselves so that every existing
// PLY/OFF scene keeps its vertex bits, and with them its hit buffers.
// Reading them correctly rounded like NFF and OBJ would be a one-line change
// here, but a visible one.
#pragma once

#include <string_view>

namespace kdrt {

// False unless the whole field is a number (ParseDouble's syntax and range).
// `Real` is the PLY property type (float or double; OFF uses float); the
// caller rounds a double to float once, as assimp did.
template <typename Real>
bool ParseAssimpDecimal(std::string_view field, Real* value);

}  // namespace kdrt
