#include <lodestone/sim/Random.h>

#include <cmath>

namespace lodestone::sim {

namespace {
std::uint64_t splitmix64(std::uint64_t& x) {
    std::uint64_t z = (x += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}
std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
}  // namespace

Random::Random(std::uint64_t seed) : seed_(seed) {
    std::uint64_t x = seed;
    for (auto& s : s_) s = splitmix64(x);
}

std::uint64_t Random::nextU64() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
}

double Random::uniform() { return static_cast<double>(nextU64() >> 11) * 0x1.0p-53; }

double Random::uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

int Random::uniformInt(int lo, int hiInclusive) {
    const auto span = static_cast<std::uint64_t>(hiInclusive - lo) + 1;
    return lo + static_cast<int>(nextU64() % span);
}

double Random::normal() {
    if (has_spare_) {
        has_spare_ = false;
        return spare_;
    }
    double u1 = uniform();
    while (u1 <= 0.0) u1 = uniform();
    const double u2 = uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * M_PI * u2);
    has_spare_ = true;
    return r * std::cos(2.0 * M_PI * u2);
}

double Random::normal(double mean, double std) { return mean + std * normal(); }

Random Random::fork(std::uint64_t streamId) const {
    std::uint64_t x = seed_ ^ (0xD1B54A32D192ED03ull * (streamId + 1));
    return Random(splitmix64(x));
}

NoiseTable::NoiseTable(std::uint64_t seed, std::size_t size) {
    std::size_t n = 1;
    while (n < size) n <<= 1;
    table_.resize(n);
    mask_ = n - 1;
    Random rng(seed);
    for (auto& v : table_) v = static_cast<float>(rng.normal());
}

std::size_t NoiseTable::randomOffset(Random& rng) const {
    return static_cast<std::size_t>(rng.nextU64()) & mask_;
}

}  // namespace lodestone::sim
