#pragma once
// --checkpoint-file and --resume, checked before anything is loaded or
// rendered: a checkpoint that cannot be written would otherwise fail only at
// the first save, mid-render.
#include <string>

namespace clpath {

// The checkpoint's folder exists and a file can be created in it (tried with
// the temporary name the writer uses); the path is not a folder. Throws
// clpath::UsageError naming --checkpoint-file when `named`, else --checkpoint.
void check_checkpoint_destination(const std::string& path, bool named);

// The file to resume exists and is a regular file; else clpath::UsageError naming --resume.
void check_resume_file(const std::string& path);

}  // namespace clpath
