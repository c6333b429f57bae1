// The per-format loaders behind LoadScene (scene.cpp picks one by extension).
// Each returns the triangles in file order and throws InputError; the rules
// common to all formats are checked in one place each (finite numbers:
// RequireFinite in text_fields.h; a non-empty scene: LoadScene).
#pragma once

#include <string>

#include "scene/scene.h"

namespace kdrt {

Scene LoadNff(const std::string& path, const LoadOptions& options);
Scene LoadObj(const std::string& path, const LoadOptions& options);
Scene LoadPly(const std::string& path, const LoadOptions& options);
Scene LoadOff(const std::string& path, const LoadOptions& options);

// Data a reader leaves out: "file:line: what" (line 0: the file) goes to
// scene->warnings, or with options.strict is thrown as an InputError with
// " (--strict)" added.
void IgnoredData(Scene* scene, const LoadOptions& options, const std::string& file, int line,
                 const std::string& what);

}  // namespace kdrt
