#pragma once
// Text outputs (CSV, Markdown) written like images: to a temporary file
// beside the target, then renamed, so a failure leaves nothing half-written.
#include <string>

namespace clpath {

// Fails early, before any work, when the folder is missing or not writable.
void check_text_output_path(const std::string& path);

// Throws clpath::Error naming the path when it cannot be written.
void write_text_file(const std::string& path, const std::string& text);

}  // namespace clpath
