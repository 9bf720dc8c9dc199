#pragma once

// sphys's version. The top-level CMakeLists.txt reads its numbers from here, so the library, its
// CMake package, `sphys --version` and Python's `sphys.__version__` all say the same; CHANGES.md
// says what changed for users in each version.

// Major version: a change of it may break code written against an earlier one.
#define SPHYS_VERSION_MAJOR 0
// Minor version: new features.
#define SPHYS_VERSION_MINOR 1
// Patch version: fixes.
#define SPHYS_VERSION_PATCH 0

// The version as one number, major * 10000 + minor * 100 + patch, for `#if` comparisons.
#define SPHYS_VERSION \
  (SPHYS_VERSION_MAJOR * 10000 + SPHYS_VERSION_MINOR * 100 + SPHYS_VERSION_PATCH)

// "major.minor.patch" of three numbers as they are written.
#define SPHYS_VERSION_TEXT_OF(major, minor, patch) #major "." #minor "." #patch
// "major.minor.patch" of three numbers, macros among them expanded first (# alone would not).
#define SPHYS_VERSION_TEXT_EXPANDED(major, minor, patch) SPHYS_VERSION_TEXT_OF(major, minor, patch)

// The version as text, "major.minor.patch".
#define SPHYS_VERSION_STRING \
  SPHYS_VERSION_TEXT_EXPANDED(SPHYS_VERSION_MAJOR, SPHYS_VERSION_MINOR, SPHYS_VERSION_PATCH)
