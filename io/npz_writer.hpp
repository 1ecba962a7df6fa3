#pragma once
// NumPy's .npz archives, written without a dependency: a ZIP file (PKWARE APPNOTE 6.3, "stored"
// entries: no compression, CRC-32 of each entry) of .npy files (NumPy's format version 1.0: the
// magic "\x93NUMPY", a header dict padded to 64 bytes, then the data, little-endian float64 in C
// order). numpy.load(path)["name"] reads each array back.
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace beamfea {

// The bytes of one .npy file holding the matrix `a` (2-D, float64, C order).
std::string npy_bytes(const Eigen::MatrixXd& a);

// The CRC-32 (ISO 3309, the ZIP checksum) of `bytes`.
std::uint32_t crc32(const std::string& bytes);

// Writes `path` atomically as an .npz of the named matrices ("<name>.npy" entries, in order).
// Throws beamfea::Error when an entry exceeds the 4 GiB of a ZIP without ZIP64.
void write_npz(const std::filesystem::path& path, const std::vector<std::pair<std::string, const Eigen::MatrixXd*>>& arrays);

}  // namespace beamfea
