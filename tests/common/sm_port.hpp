// Bit-level access to Verilated ports of any width: integral types (CData..QData) for
// ports up to 64 bits, VlWide (32-bit words) above.
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

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

}  // namespace sm::test
