// SPDX-License-Identifier: GPL-3.0-or-later
// gzip-compressed mesh files (.off.gz, .stl.gz, ...) through zlib: read within the input size
// limit (a small file can inflate to gigabytes), written whole.
#include <zlib.h>

#include <cstring>

#include "mesh/io_text.h"

namespace morphex::detail {

bool is_gzip(const std::string& content) {
  return content.size() >= 2 && static_cast<unsigned char>(content[0]) == 0x1f &&
         static_cast<unsigned char>(content[1]) == 0x8b;
}

std::string gunzip(const std::string& content, const std::string& name, std::uint64_t limit) {
  z_stream z{};
  if (inflateInit2(&z, 15 + 16) != Z_OK) throw std::bad_alloc();
  struct End {
    z_stream& z;
    ~End() { inflateEnd(&z); }
  } end{z};
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(content.data()));
  z.avail_in = uInt(content.size());  // mesh files are below 4 GiB (the input limit)
  std::string out;
  char chunk[1 << 16];
  for (;;) {
    z.next_out = reinterpret_cast<Bytef*>(chunk);
    z.avail_out = sizeof chunk;
    const int status = inflate(&z, Z_NO_FLUSH);
    if (status != Z_OK && status != Z_STREAM_END && !(status == Z_BUF_ERROR && z.avail_in == 0))
      throw InputError(name, std::string("corrupt gzip data: ") +
                                 (z.msg ? z.msg : "inflate failed") + " after " +
                                 std::to_string(out.size()) + " bytes");
    out.append(chunk, sizeof chunk - z.avail_out);
    if (out.size() > limit)
      throw InputError(name, "file too large once decompressed: more than " +
                                 std::to_string(limit) +
                                 " bytes (raise the limit with --max-input-mb)");
    if (status == Z_STREAM_END) {
      if (z.avail_in == 0) return out;
      if (inflateReset(&z) != Z_OK) throw std::bad_alloc();  // another gzip member follows
      continue;
    }
    if (status == Z_BUF_ERROR || (z.avail_in == 0 && z.avail_out != 0))
      throw InputError(name, "truncated gzip data after " + std::to_string(out.size()) + " bytes");
  }
}

std::string gzip(const std::string& content) {
  z_stream z{};
  if (deflateInit2(&z, Z_DEFAULT_COMPRESSION, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK)
    throw std::bad_alloc();
  std::string out(deflateBound(&z, uLong(content.size())), '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(content.data()));
  z.avail_in = uInt(content.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = uInt(out.size());
  const int status = deflate(&z, Z_FINISH);
  out.resize(out.size() - z.avail_out);
  deflateEnd(&z);
  if (status != Z_STREAM_END) throw std::runtime_error("gzip compression failed");
  return out;
}

}  // namespace morphex::detail
