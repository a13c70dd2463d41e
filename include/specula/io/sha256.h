#pragma once
// SHA-256 (FIPS 180-4), for the provenance of the files specula writes: a table's values hashed so
// that a copy can be told from the original (docs/energy-compensation.md, `specula lut`).
#include <cstddef>
#include <span>
#include <string>

namespace specula::io {

/// The SHA-256 digest of `bytes` as 64 lowercase hex digits.
std::string sha256_hex(std::span<const std::byte> bytes);

/// Doubles as little-endian IEEE 754 binary64 bytes, in order: the same on any machine.
std::string little_endian_bytes(std::span<const double> values);

/// The digest of little_endian_bytes(values).
std::string sha256_of_doubles(std::span<const double> values);

}  // namespace specula::io
