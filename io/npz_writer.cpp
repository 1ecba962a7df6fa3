#include "io/npz_writer.hpp"

#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>

#include "core/errors.hpp"
#include "io/atomic_file.hpp"

namespace beamfea {

namespace {

static_assert(std::endian::native == std::endian::little, "the .npy data are written as the machine's doubles");

// NumPy's .npy version 1.0: the magic string, the version, a 2-byte header length; the whole
// preamble is padded with spaces (ending in a newline) to a multiple of this many bytes.
constexpr std::size_t kNpyAlignment = 64;
// DOS date of 1980-01-01 00:00 (the ZIP's earliest): the archive's entries carry no real time, so
// that the same arrays give the same bytes.
constexpr std::uint16_t kDosDate = (0 << 9) | (1 << 5) | 1;
// "version needed to extract": 2.0 (stored entries).
constexpr std::uint16_t kZipVersion = 20;

void put16(std::string& s, std::uint16_t v) {
  s.push_back(static_cast<char>(v & 0xff));
  s.push_back(static_cast<char>(v >> 8));
}
void put32(std::string& s, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) s.push_back(static_cast<char>((v >> (8 * k)) & 0xff));
}

std::array<std::uint32_t, 256> crc_table() {
  std::array<std::uint32_t, 256> t{};
  for (std::uint32_t n = 0; n < 256; ++n) {
    std::uint32_t c = n;
    for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;  // reflected polynomial 0x04C11DB7
    t[n] = c;
  }
  return t;
}

std::uint32_t checked32(std::size_t n) {
  if (n >= std::numeric_limits<std::uint32_t>::max()) throw Error(".npz: an array exceeds 4 GiB (ZIP64 is not written)");
  return static_cast<std::uint32_t>(n);
}

}  // namespace

std::uint32_t crc32(const std::string& bytes) {
  static const std::array<std::uint32_t, 256> table = crc_table();
  std::uint32_t c = 0xffffffffu;
  for (const char ch : bytes) c = table[(c ^ static_cast<unsigned char>(ch)) & 0xff] ^ (c >> 8);
  return c ^ 0xffffffffu;
}

std::string npy_bytes(const Eigen::MatrixXd& a) {
  std::string header = "{'descr': '<f8', 'fortran_order': False, 'shape': (" + std::to_string(a.rows()) + ", " +
                       std::to_string(a.cols()) + "), }";
  const std::size_t preamble = 10;  // magic (6), version (2), header length (2)
  const std::size_t padded = (preamble + header.size() + 1 + kNpyAlignment - 1) / kNpyAlignment * kNpyAlignment;
  header.append(padded - preamble - header.size() - 1, ' ');
  header.push_back('\n');
  std::string s("\x93NUMPY\x01\x00", 8);
  put16(s, static_cast<std::uint16_t>(header.size()));
  s += header;
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> c = a;  // C order
  const std::size_t at = s.size();
  s.resize(at + sizeof(double) * static_cast<std::size_t>(c.size()));
  if (c.size() > 0) std::memcpy(s.data() + at, c.data(), sizeof(double) * static_cast<std::size_t>(c.size()));
  return s;
}

void write_npz(const std::filesystem::path& path, const std::vector<std::pair<std::string, const Eigen::MatrixXd*>>& arrays) {
  std::string zip, central;
  for (const auto& [name, matrix] : arrays) {
    const std::string file = name + ".npy";
    const std::string data = npy_bytes(*matrix);
    const std::uint32_t crc = crc32(data), size = checked32(data.size()), offset = checked32(zip.size());
    // Local file header (APPNOTE 4.3.7).
    put32(zip, 0x04034b50);
    put16(zip, kZipVersion);
    put16(zip, 0);  // flags
    put16(zip, 0);  // method: stored
    put16(zip, 0);  // time
    put16(zip, kDosDate);
    put32(zip, crc);
    put32(zip, size);
    put32(zip, size);
    put16(zip, static_cast<std::uint16_t>(file.size()));
    put16(zip, 0);  // extra field length
    zip += file;
    zip += data;
    // Its central directory entry (APPNOTE 4.3.12).
    put32(central, 0x02014b50);
    put16(central, kZipVersion);  // made by
    put16(central, kZipVersion);
    put16(central, 0);
    put16(central, 0);
    put16(central, 0);
    put16(central, kDosDate);
    put32(central, crc);
    put32(central, size);
    put32(central, size);
    put16(central, static_cast<std::uint16_t>(file.size()));
    put16(central, 0);  // extra
    put16(central, 0);  // comment
    put16(central, 0);  // disk number
    put16(central, 0);  // internal attributes
    put32(central, 0);  // external attributes
    put32(central, offset);
    central += file;
  }
  const std::uint32_t central_offset = checked32(zip.size()), central_size = checked32(central.size());
  zip += central;
  // End of central directory (APPNOTE 4.3.16).
  put32(zip, 0x06054b50);
  put16(zip, 0);
  put16(zip, 0);
  put16(zip, static_cast<std::uint16_t>(arrays.size()));
  put16(zip, static_cast<std::uint16_t>(arrays.size()));
  put32(zip, central_size);
  put32(zip, central_offset);
  put16(zip, 0);  // comment length
  write_atomic(path, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out.write(zip.data(), static_cast<std::streamsize>(zip.size()));
    if (!out) throw Error("cannot write " + tmp.string());
  });
}

}  // namespace beamfea
