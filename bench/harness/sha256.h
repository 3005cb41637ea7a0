// SHA-256 (FIPS 180-4) of a byte string, as 64 lowercase hex digits: the fingerprint run.json
// records of the problem file and meshes a run read, so that `contactbench rerun` can tell
// that their copies are the files the run used.
#pragma once

#include <string>
#include <string_view>

namespace cb::harness {

std::string Sha256Hex(std::string_view bytes);

}  // namespace cb::harness
