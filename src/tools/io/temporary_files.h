#pragma once

// The names of the temporary files sphys writes next to its outputs, and the removal of those a
// process left behind when it was killed before it could remove them itself.

#include <filesystem>

namespace sphys::tools {

// A fresh name next to `target`, so that a rename into place stays within one file system:
// "<target>.sphys-<process id>-<random hex>.tmp". The process id says whose file it is.
[[nodiscard]] std::filesystem::path temporary_sibling(const std::filesystem::path& target);

// Removes from `directory` the temporary files (named as above) whose process has ended, with a
// note on standard error for each; files of running processes, and of processes this one may not
// signal, stay. Looks at each directory once per process.
void remove_orphaned_temporaries(const std::filesystem::path& directory);

}  // namespace sphys::tools
