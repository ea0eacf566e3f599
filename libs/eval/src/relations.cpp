#include "gridtopo/eval/relations.h"

#include <zlib.h>

#include <charconv>
#include <cmath>
#include <string_view>

#include "gridtopo/core/error.h"

namespace gridtopo::eval {

std::string readMaybeGzipped(const std::string& path) {
  gzFile g = gzopen(path.c_str(), "rb");  // reads plain files transparently
  if (!g) throw InputError(path, "cannot open file");
  gzbuffer(g, 1 << 17);
  std::string out;
  char buf[1 << 16];
  for (;;) {
    const int n = gzread(g, buf, sizeof buf);
    if (n > 0) out.append(buf, static_cast<std::size_t>(n));
    if (n < static_cast<int>(sizeof buf)) {
      int err = Z_OK;
      const char* msg = gzerror(g, &err);
      const bool direct = gzdirect(g) != 0;
      gzclose(g);
      // Z_BUF_ERROR at the end of input: the gzip stream stopped before its end (truncated file).
      if (err == Z_BUF_ERROR && !direct) throw InputError(path, 0, "gzip", "truncated compressed file");
      if (n < 0 || (err != Z_OK && err != Z_BUF_ERROR))
        throw InputError(path, 0, "gzip", std::string("corrupt or unreadable file: ") + (msg ? msg : ""));
      return out;
    }
  }
}

std::vector<Relation> parseRelations(const std::string& text, const std::string& name) {
  static const char* kFields[] = {"t1", "t2", "x", "y", "z", "roll", "pitch", "yaw"};
  std::vector<Relation> out;
  std::size_t pos = 0, lineno = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    ++lineno;
    const char* p = text.data() + pos;
    const char* e = text.data() + end;
    pos = end + 1;
    auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
    while (p < e && is_space(*p)) ++p;
    if (p == e || *p == '#') continue;
    double v[8];
    for (int i = 0; i < 8; ++i) {
      while (p < e && is_space(*p)) ++p;
      if (p == e) throw InputError(name, lineno, kFields[i], "missing (expected t1 t2 x y z roll pitch yaw)");
      const char* b = p;
      while (p < e && !is_space(*p)) ++p;
      const char* tb = (*b == '+') ? b + 1 : b;
      const auto res = std::from_chars(tb, p, v[i]);
      if (res.ec != std::errc() || res.ptr != p || tb == p || !std::isfinite(v[i]))
        throw InputError(name, lineno, kFields[i], "not a finite number ('" + std::string(b, p) + "')");
    }
    while (p < e && is_space(*p)) ++p;
    if (p != e) throw InputError(name, lineno, "line", "unexpected text after yaw");
    Relation r;
    r.t1 = v[0];
    r.t2 = v[1];
    r.delta = {v[2], v[3], v[7]};
    r.line = lineno;
    out.push_back(r);
  }
  return out;
}

std::vector<Relation> readRelations(const std::string& path) { return parseRelations(readMaybeGzipped(path), path); }

}  // namespace gridtopo::eval
