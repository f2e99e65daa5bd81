#pragma once
namespace vgi {
// `git describe` of the source tree at build time ("unknown" outside git).
const char* gitRevision();
// The project version (CMake project(VERSION)).
const char* version();
}  // namespace vgi
