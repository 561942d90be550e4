// Output paths are checked before any work starts (GL set-up, data loading, tracing), so a
// typo in --out or --report fails in milliseconds with the reason, not after a long run.
#pragma once

#include <string>

namespace pathlet {

// Makes sure `dir` is a folder this process can create files in: creates it (and its
// parents) when missing, then creates and removes a probe file. Throws std::runtime_error
// "cannot write <what> to '<dir>': <reason>" (reason from the OS: permission denied,
// read-only file system, not a folder, ...).
// With keep = false the folders the check made are removed again: nothing is left before the
// inputs are known good (the writers make the folder when they write into it).
void check_output_dir(const std::string& dir, const std::string& what, bool keep = true);

// The same for the folder that will hold the file `path` (the current folder when the
// path has none); also rejects a path that names an existing folder.
void check_output_file(const std::string& path, const std::string& what, bool keep = true);

}  // namespace pathlet
