#pragma once
// Benchmark outputs (CSV, Markdown): checked before a run starts, so a long
// benchmark never fails at its end, and written through a temporary file and
// a rename, so no half-written table is ever left behind.
#include <string>

namespace clpath {

// Throws clpath::Error naming the path when its folder is missing or not
// writable, or when the path is a folder. what: "--csv", "--md", ...
void check_report_path(const std::string& path, const std::string& what);

// Writes text to path atomically; throws clpath::Error on failure.
void write_report_file(const std::string& path, const std::string& text);

// A CSV field: quoted when it holds a comma, a quote or a newline (RFC 4180).
std::string csv_field(const std::string& s);

}  // namespace clpath
