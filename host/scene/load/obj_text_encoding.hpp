#pragma once
// OBJ and MTL files as the line checks read them: UTF-8 without a byte-order
// mark. Windows tools write UTF-8 with a mark, or UTF-16 with one; assimp
// reads both, so clpath does too.
#include <string>

namespace clpath {

// The text as UTF-8: a UTF-8 mark dropped, UTF-16 (little- or big-endian,
// told by its mark) converted. Text without a mark is returned as it is.
// Throws clpath::Error naming file for UTF-16 that is cut short or has an
// unpaired surrogate.
std::string obj_text_as_utf8(std::string bytes, const std::string& file);

}  // namespace clpath
