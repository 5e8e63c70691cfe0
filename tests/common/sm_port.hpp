// Bit-level access to Verilated ports of any width: integral types (CData..QData) for
// ports up to 64 bits, VlWide (32-bit words) above.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace sm::test {

// Field [lo, lo + n) of a Verilated port, n <= 32.
template <typename T>
unsigned port_bits(const T& sig, int lo, int n) {
  uint64_t v;
  if constexpr (std::is_integral_v<T>) {
    v = static_cast<uint64_t>(sig) >> lo;
  } else {
    const int i = lo / 32;
    v = sig[i];
    if (static_cast<size_t>(i + 1) < sizeof(sig) / sizeof(sig[0]) && lo % 32 + n > 32)
      v |= static_cast<uint64_t>(sig[i + 1]) << 32;
    v >>= lo % 32;
  }
  return static_cast<unsigned>(v & ((uint64_t{1} << n) - 1));
}

// Lane `lane` of a port in bit-plane order (bit f of lane l at [f*lanes + l]), n <= 32
// bits: sm_cost's and sm_sw_aggregate's per-level costs.
template <typename T>
unsigned plane_bits(const T& sig, int lane, int n, int lanes) {
  unsigned v = 0;
  for (int f = 0; f < n; ++f) v |= port_bits(sig, f * lanes + lane, 1) << f;
  return v;
}

// Set or clear bit i of a Verilated port.
template <typename T>
void set_port_bit(T& sig, int i, bool v) {
  if constexpr (std::is_integral_v<T>) {
    const T m = static_cast<T>(T{1} << i);
    sig = v ? static_cast<T>(sig | m) : static_cast<T>(sig & ~m);
  } else {
    const uint32_t m = uint32_t{1} << (i % 32);
    sig[i / 32] = v ? (sig[i / 32] | m) : (sig[i / 32] & ~m);
  }
}

// Word i of a `width`-bit value held in 32-bit words w (missing words are 0, bits at and
// above `width` cleared: Verilator expects a port's unused top bits to be zero).
inline uint32_t port_word(const std::vector<uint32_t>& w, int i, int width) {
  uint32_t v = static_cast<size_t>(i) < w.size() ? w[static_cast<size_t>(i)] : 0u;
  if (32 * (i + 1) > width) v &= (uint32_t{1} << (width % 32)) - 1;
  return v;
}

// n values of `bits` bits each as 32-bit port words, value k at bit k * bits (the DISP
// CW-bit costs of sm_dp's, sm_wta's and sm_right_wta's s_cost).
inline std::vector<uint32_t> pack_values(const uint8_t* v, int n, int bits) {
  std::vector<uint32_t> w(static_cast<size_t>((n * bits + 31) / 32), 0u);
  for (int k = 0; k < n; ++k)
    for (int b = 0; b < bits; ++b)
      if ((v[k] >> b) & 1) w[static_cast<size_t>((k * bits + b) / 32)] |= 1u << ((k * bits + b) % 32);
  return w;
}

// Drive a `width`-bit Verilated input port from 32-bit words (bit b at word b / 32).
template <typename T>
void set_port_words(T& port, const std::vector<uint32_t>& w, int width) {
  if constexpr (std::is_integral_v<T>) {
    uint64_t v = port_word(w, 0, width);
    if (width > 32) v |= static_cast<uint64_t>(port_word(w, 1, width)) << 32;
    port = static_cast<T>(v);
  } else {
    for (int i = 0; i < (width + 31) / 32; ++i) port[i] = port_word(w, i, width);
  }
}

// The `width` bits of a Verilated port as 32-bit words.
template <typename T>
std::vector<uint32_t> get_port_words(const T& port, int width) {
  std::vector<uint32_t> w(static_cast<size_t>((width + 31) / 32), 0u);
  if constexpr (std::is_integral_v<T>) {
    const uint64_t v = static_cast<uint64_t>(port);
    w[0] = static_cast<uint32_t>(v);
    if (w.size() > 1) w[1] = static_cast<uint32_t>(v >> 32);
  } else {
    for (size_t i = 0; i < w.size(); ++i) w[i] = port[i];
  }
  for (size_t i = 0; i < w.size(); ++i) w[i] = port_word(w, static_cast<int>(i), width);
  return w;
}

// The same for values held in 64-bit words (e.g. the model's census vectors).
template <typename T, size_t N>
void set_port_u64(T& port, const std::array<uint64_t, N>& v, int width) {
  std::vector<uint32_t> w(2 * N);
  for (size_t i = 0; i < N; ++i) {
    w[2 * i] = static_cast<uint32_t>(v[i]);
    w[2 * i + 1] = static_cast<uint32_t>(v[i] >> 32);
  }
  set_port_words(port, w, width);
}
template <size_t N, typename T>
std::array<uint64_t, N> get_port_u64(const T& port, int width) {
  const std::vector<uint32_t> w = get_port_words(port, width);
  std::array<uint64_t, N> v{};
  for (size_t i = 0; i < w.size() && i / 2 < N; ++i) v[i / 2] |= static_cast<uint64_t>(w[i]) << (32 * (i % 2));
  return v;
}

}  // namespace sm::test
