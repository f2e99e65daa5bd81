// Warnings a person sees: what a scene or an option produced that changes what is rendered but does
// not stop it (a material's ks reduced, a light added, a model's missing texture). Each is recorded
// where it arose (a scene's LoadReport, a render's stats "warnings") and printed here, to stderr, once
// per process, under --quiet too (which silences progress, not problems).
#pragma once
#include <string>
#include <vector>

namespace vgi {

// Prints "vgi: warning: TEXT" to stderr unless this process printed the same text before (a compare
// loads its scene twice; a viewer reloads it). Thread-safe.
void printWarning(const std::string& text);
void printWarnings(const std::vector<std::string>& texts);

}  // namespace vgi
