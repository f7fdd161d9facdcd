// Internal: a counter-based random stream. Every number is a pure function of (seed, stream,
// counter): no generator state is carried from one draw to the next, so a Monte Carlo trial gives
// the same draws whichever thread or process runs it, in whatever order (monte_carlo.h). The bits
// are SplitMix64's finaliser (Steele, Lea, Flood 2014) applied twice to the keyed counter; the
// normal deviates use Box-Muller on two such uniforms, so no library distribution (whose
// algorithm the C++ standard leaves open) is involved.
#pragma once

#include <cmath>
#include <cstdint>

namespace plateball::internal {

inline std::uint64_t SplitMix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

class CounterRandom {
 public:
  CounterRandom(std::uint64_t seed, std::uint64_t stream)
      : key_(SplitMix64(SplitMix64(seed) ^ (stream * 0xd1b54a32d192ed03ULL + 0x8cb92ba72f3d8dd7ULL))) {}

  /// 64 random bits for `counter`.
  std::uint64_t Bits(std::uint64_t counter) const { return SplitMix64(SplitMix64(key_ ^ counter) + counter); }

  /// Uniform in the open interval (0, 1), 53 random bits.
  double Uniform(std::uint64_t counter) const { return (static_cast<double>(Bits(counter) >> 11) + 0.5) * 0x1.0p-53; }

  /// A standard normal deviate for `counter` (Box-Muller on the uniforms of 2 counter and 2 counter + 1).
  double Normal(std::uint64_t counter) const {
    const double u1 = Uniform(2 * counter), u2 = Uniform(2 * counter + 1);
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }

 private:
  std::uint64_t key_;
};

}  // namespace plateball::internal
