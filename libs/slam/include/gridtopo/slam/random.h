#pragma once
// Our own small random number generator (xoshiro256++ seeded through SplitMix64) and samplers, so that the
// filter's output is identical on every platform and standard library, and so that every particle draws from
// its own stream seeded from (seed, step, particle): no shared generator, so results do not depend on threads.
#include <cmath>
#include <cstdint>

namespace gridtopo::slam {

class Rng {
 public:
  /// A stream identified by a run seed and up to three stream coordinates (e.g. step, particle, purpose).
  explicit Rng(std::uint64_t seed, std::uint64_t a = 0, std::uint64_t b = 0, std::uint64_t c = 0) {
    std::uint64_t sm = seed;
    sm = mix(sm ^ mix(a + 0x9E3779B97F4A7C15ULL));
    sm = mix(sm ^ mix(b + 0xD1B54A32D192ED03ULL));
    sm = mix(sm ^ mix(c + 0x8CB92BA72F3D8DD7ULL));
    for (auto& w : s_) w = splitmix(sm);
  }

  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[0] + s_[3], 23) + s_[0];
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  /// Uniform in [0, 1).
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  /// Standard normal (Box-Muller, both values used).
  double gaussian() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u1 = uniform();
    while (u1 <= 0.0) u1 = uniform();
    const double u2 = uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    const double a = 6.283185307179586 * u2;
    spare_ = r * std::sin(a);
    has_spare_ = true;
    return r * std::cos(a);
  }
  double gaussian(double sigma) { return sigma * gaussian(); }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  static std::uint64_t mix(std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  static std::uint64_t splitmix(std::uint64_t& x) { return mix(x += 0x9E3779B97F4A7C15ULL); }
  std::uint64_t s_[4];
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace gridtopo::slam
