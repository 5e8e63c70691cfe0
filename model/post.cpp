#include "post.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <utility>

// Speed (docs/performance.md): the rank filter runs on vectors of keys, and on x86-64
// with GCC its loop is also compiled for AVX2 and picked at run time (SM_HOT in
// kernels.hpp); integer min/max only, so both clones give the same bits.
#include "kernels.hpp"
#include "parallel.hpp"

namespace sm {

namespace {
// the level bits of a stream word: the low clog2(DISP)
unsigned level_mask(const HwConfig& hw) { return (1u << clog2(hw.disp)) - 1; }
}  // namespace

DispImage post_median(const DispImage& in, const HwConfig& hw, int ry, int rx) {
  return post_rank(in, hw, ry, rx, (2 * ry + 1) * (2 * rx + 1) / 2);
}

namespace {

// Batcher's odd-even merge sort network for n (a power of two) elements: compare-
// exchange pairs (i, j), i < j, in an order that sorts any input ascending.
std::vector<std::pair<int, int>> sort_network(int n) {
  std::vector<std::pair<int, int>> net;
  for (int p = 1; p < n; p <<= 1)
    for (int k = p; k >= 1; k >>= 1)
      for (int j = k % p; j + k < n; j += 2 * k)
        for (int i = 0; i < std::min(k, n - j - k); ++i)
          if ((i + j) / (2 * p) == (i + j + k) / (2 * p)) net.emplace_back(i + j, i + j + k);
  return net;
}

// The comparators of `net` (n2 inputs) that the element of rank `rank` depends on when
// inputs n..n2-1 are the largest possible key (the padding): a comparator with a padding
// input is a no-op or an exchange (done by renaming, not by moving data), and one whose
// outputs are not needed later is dropped. Same result as the whole network on every
// input; `out` is where the element of rank `rank` ends up.
std::vector<std::pair<int, int>> prune_network(const std::vector<std::pair<int, int>>& net, int n, int n2, int rank,
                                               int& out) {
  std::vector<int> at(static_cast<size_t>(n2));  // logical position -> slot
  std::vector<char> pad(static_cast<size_t>(n2));
  for (int k = 0; k < n2; ++k) {
    at[static_cast<size_t>(k)] = k;
    pad[static_cast<size_t>(k)] = k >= n;
  }
  std::vector<std::pair<int, int>> kept;
  for (const auto& [i, j] : net) {
    auto &si = at[static_cast<size_t>(i)], &sj = at[static_cast<size_t>(j)];
    if (pad[static_cast<size_t>(sj)]) continue;  // min(a, MAX) = a: stays in place
    if (pad[static_cast<size_t>(si)]) {          // the key moves up, the padding down
      std::swap(si, sj);
      continue;
    }
    kept.emplace_back(si, sj);
  }
  out = at[static_cast<size_t>(rank)];
  std::vector<char> live(static_cast<size_t>(n2), 0);
  live[static_cast<size_t>(out)] = 1;
  std::vector<std::pair<int, int>> need;
  for (auto c = kept.rbegin(); c != kept.rend(); ++c)
    if (live[static_cast<size_t>(c->first)] || live[static_cast<size_t>(c->second)]) {
      live[static_cast<size_t>(c->first)] = live[static_cast<size_t>(c->second)] = 1;
      need.push_back(*c);
    }
  std::reverse(need.begin(), need.end());
  return need;
}

#if defined(__GNUC__)
typedef uint16_t VK __attribute__((vector_size(32)));  // keys of 16 neighbouring centres
constexpr int kKeyLanes = 16;
constexpr int kMaxNet = 64;  // windows up to 8 x 8 take the vector path

// Rank filter of the centres x0, x0 + 16, ... of row y whose whole window lies inside
// the columns (x0 >= rx, x + 16 + rx <= w); returns the first centre not done. Sixteen
// centres at a time through a sorting network on vectors of keys (min/max only; the
// element of rank `rank` of the sorted window is the answer whatever the order of
// equal keys). The network has n2 = the next power of two inputs; the extra ones are
// 0xffff and sort behind every key (keys are at most 2^15), which prune_network uses;
// the answer is in v[slot]. Window rows outside the frame take the centre's key: the
// centre vector itself.
SM_HOT int rank_row(const uint16_t* keys, int w, int h, int y, int x0, int ry, int rx, int slot, int n2,
                    const std::pair<int, int>* net, size_t net_size, DispPix* out) {
  VK v[kMaxNet];
  int x = x0;
  for (; x + kKeyLanes + rx <= w; x += kKeyLanes) {
    VK centre;
    std::memcpy(&centre, keys + static_cast<size_t>(y) * w + x, sizeof centre);
    int k = 0;
    for (int j = -ry; j <= ry; ++j) {
      const bool row_in = y + j >= 0 && y + j < h;
      for (int i = -rx; i <= rx; ++i, ++k) {
        if (row_in)
          std::memcpy(&v[k], keys + static_cast<size_t>(y + j) * w + x + i, sizeof(VK));
        else
          v[k] = centre;
      }
    }
    for (; k < n2; ++k) v[k] = VK{} + 0xffff;
    for (size_t c = 0; c < net_size; ++c) {
      const VK a = v[net[c].first], b = v[net[c].second];
      v[net[c].first] = a < b ? a : b;
      v[net[c].second] = a < b ? b : a;
    }
    const VK m = v[slot];
    const VK o = m == 0 ? VK{} : ((m - 1) | kDispValid);
    std::memcpy(out + x, &o, sizeof o);
  }
  return x;
}

// The chain's three medians (5 x 1, 3 x 3, 5 x 3) with the network known at compile time:
// unrolled, every index is a constant, so the window's vectors stay in registers (rank_row
// reads and writes them in memory at every compare-exchange, its network chosen at run
// time) and the compiler drops the exchanges that the median and the 0xffff padding do not
// need. Batcher's network (sort_network) on the next power of two inputs; any sorting
// network leaves the same value at each rank, so the same bits as rank_row.
template <int N2>
struct StaticNet {
  int n = 0;
  int a[N2 * N2] = {}, b[N2 * N2] = {};
  constexpr StaticNet() {
    for (int p = 1; p < N2; p <<= 1)
      for (int k = p; k >= 1; k >>= 1)
        for (int j = k % p; j + k < N2; j += 2 * k)
          for (int i = 0; i < std::min(k, N2 - j - k); ++i)
            if ((i + j) / (2 * p) == (i + j + k) / (2 * p)) {
              a[n] = i + j;
              b[n] = i + j + k;
              ++n;
            }
  }
};

// As rank_row for the median of a (2 RY + 1) x (2 RX + 1) window, L = the lanes of V.
template <class V, int RY, int RX>
inline __attribute__((always_inline)) int median_row_t(const uint16_t* keys, int w, int h, int y, int x0,
                                                       DispPix* out) {
  constexpr int L = sizeof(V) / 2, n = (2 * RY + 1) * (2 * RX + 1), n2 = n <= 8 ? 8 : 16;
  static_assert(n <= n2, "window larger than the network");
  static constexpr StaticNet<n2> net{};
  int x = x0;
  for (; x + L + RX <= w; x += L) {
    V v[n2];
    std::memcpy(&v[n / 2], keys + static_cast<size_t>(y) * w + x, sizeof(V));  // the centre
    for (int j = -RY; j <= RY; ++j) {
      const bool row_in = y + j >= 0 && y + j < h;
      for (int i = -RX; i <= RX; ++i) {
        const int k = (j + RY) * (2 * RX + 1) + (i + RX);
        if (row_in)
          std::memcpy(&v[k], keys + static_cast<size_t>(y + j) * w + x + i, sizeof(V));
        else
          v[k] = v[n / 2];  // a row outside the frame takes the centre's key
      }
    }
    for (int k = n; k < n2; ++k) v[k] = V{} + 0xffff;
#pragma GCC unroll 128
    for (int c = 0; c < net.n; ++c) {
      const V a = v[net.a[c]], b = v[net.b[c]];
      v[net.a[c]] = a < b ? a : b;
      v[net.b[c]] = a < b ? b : a;
    }
    const V m = v[n / 2];
    const V o = m == 0 ? V{} : ((m - 1) | kDispValid);
    std::memcpy(out + x, &o, sizeof o);
  }
  return x;
}
#endif

#if defined(__GNUC__)
// median_row_t for the chain's windows; -1 for another window (rank_row then).
SM_HOT int median_row(int ry, int rx, const uint16_t* keys, int w, int h, int y, int x0, DispPix* out) {
  if (ry == 2 && rx == 0) return median_row_t<VK, 2, 0>(keys, w, h, y, x0, out);
  if (ry == 1 && rx == 1) return median_row_t<VK, 1, 1>(keys, w, h, y, x0, out);
  if (ry == 2 && rx == 1) return median_row_t<VK, 2, 1>(keys, w, h, y, x0, out);
  return -1;
}
#endif

}  // namespace

namespace {
DispImage post_rank_rows(const DispImage& in, const HwConfig& hw, int ry, int rx, int rank, int threads) {
  const unsigned dmask = level_mask(hw);
  auto key = [&](DispPix p) -> unsigned { return disp_valid(p) ? (p & dmask) + 1 : 0; };
  const int n = (2 * ry + 1) * (2 * rx + 1);
  if (rank < 0 || rank >= n) throw std::invalid_argument("post_rank: rank outside the window");
  const int w = in.w, h = in.h;
  DispImage out(w, h);

  // One centre, straight from the definition (image edges, leftover columns, windows
  // too large for the network).
  auto one = [&](std::vector<unsigned>& win, int x, int y) {
    const unsigned c = key(in.at(x, y));
    win.clear();
    for (int j = -ry; j <= ry; ++j)
      for (int i = -rx; i <= rx; ++i) {
        const int xx = x + i, yy = y + j;
        const bool inside = xx >= 0 && xx < w && yy >= 0 && yy < h;
        win.push_back(inside ? key(in.at(xx, yy)) : c);
      }
    std::nth_element(win.begin(), win.begin() + rank, win.end());
    const unsigned m = win[static_cast<size_t>(rank)];
    out.at(x, y) = m == 0 ? DispPix{0} : make_disp(m - 1, true);
  };

#if defined(__GNUC__)
  int n2 = 1;
  while (n2 < n) n2 <<= 1;
  const bool vec = n2 <= kMaxNet && dmask < 0x8000;  // keys <= 2^15 (any DISP <= 2^15)
  if (vec) {
    std::vector<uint16_t> keys(in.px.size());
    parallel_bands(h, threads, [&](int y0, int y1, int) {
      for (size_t i = static_cast<size_t>(y0) * w; i < static_cast<size_t>(y1) * w; ++i)
        keys[i] = static_cast<uint16_t>(key(in.px[i]));
    });
    int slot = 0;
    const auto net = prune_network(sort_network(n2), n, n2, rank, slot);
    const bool median = rank == n / 2;
    parallel_bands(h, threads, [&](int y0, int y1, int) {
      std::vector<unsigned> win;
      for (int y = y0; y < y1; ++y) {
        int x = 0;
        for (; x < std::min(rx, w); ++x) one(win, x, y);
        DispPix* o = &out.px[static_cast<size_t>(y) * w];
        // The centres whose window lies inside the columns, then the columns left over:
        // one more block ending at the last such centre (recomputing some centres, with the
        // same result).
        auto block = [&](int x0) {
          const int e = median ? median_row(ry, rx, keys.data(), w, h, y, x0, o) : -1;
          return e >= 0 ? e : rank_row(keys.data(), w, h, y, x0, ry, rx, slot, n2, net.data(), net.size(), o);
        };
        x = block(x);
        if (x < w - rx && w - rx - kKeyLanes >= rx) x = block(w - rx - kKeyLanes);
        for (; x < w; ++x) one(win, x, y);
      }
    });
    return out;
  }
#endif
  parallel_bands(h, threads, [&](int y0, int y1, int) {
    std::vector<unsigned> win;
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < w; ++x) one(win, x, y);
  });
  return out;
}
}  // namespace

DispImage post_rank(const DispImage& in, const HwConfig& hw, int ry, int rx, int rank) {
  return post_rank_rows(in, hw, ry, rx, rank, 1);
}

DispImage post_vmedian(const DispImage& in, const HwConfig& hw) { return post_median(in, hw, 2, 0); }
DispImage post_median3(const DispImage& in, const HwConfig& hw) { return post_median(in, hw, 1, 1); }
DispImage post_median53(const DispImage& in, const HwConfig& hw) { return post_median(in, hw, 2, 1); }

namespace {
// post_band on bands of columns (each column is a recursion of its own, top to bottom).
DispImage post_band_cols(const DispImage& in, const HwConfig& hw, int k, int threads) {
  if (k < 0) throw std::invalid_argument("post_band: negative look-ahead");
  const int dmask = static_cast<int>(level_mask(hw));
  auto d = [dmask](DispPix p) { return static_cast<int>(p) & dmask; };
  // Output words as the medians': valid -> 0x8000 | d, invalid -> 0x0000.
  auto norm = [&](DispPix p) { return disp_valid(p) ? make_disp(static_cast<unsigned>(d(p)), true) : DispPix{0}; };
  DispImage out(in.w, in.h);
  parallel_bands(in.w, threads, [&](int x0, int x1, int) {
    for (int x = x0; x < x1 && in.h > 0; ++x) out.at(x, 0) = norm(in.at(x, 0));
    for (int y = 1; y < in.h; ++y)
      for (int x = x0; x < x1; ++x) {
        const DispPix a = out.at(x, y - 1), c = in.at(x, y);
        out.at(x, y) = norm(c);
        if (!disp_valid(a) || !disp_valid(c) || std::abs(d(c) - d(a)) <= 1) continue;
        for (int j = 1; j <= k && y + j < in.h; ++j) {
          const DispPix b = in.at(x, y + j);
          if (disp_valid(b) && std::abs(d(b) - d(a)) <= 1) {
            out.at(x, y) = a;
            break;
          }
        }
      }
  });
  return out;
}
}  // namespace

DispImage post_band(const DispImage& in, const HwConfig& hw, int k) { return post_band_cols(in, hw, k, 1); }

DispImage post_bypass(const DispImage& in, const HwConfig& hw) {
  const DispPix keep = static_cast<DispPix>(kDispValid | level_mask(hw));
  DispImage out(in.w, in.h);
  for (size_t i = 0; i < in.px.size(); ++i) out.px[i] = in.px[i] & keep;
  return out;
}

DispImage post_process(const DispImage& in, const Regs& regs, const HwConfig& hw, std::vector<DispImage>* steps,
                       int threads) {
  // Each step's image is made in place in the list of steps (a copy only for a disabled
  // filter and for the result: copies of whole frames were a serial part of a threaded run).
  std::vector<DispImage> own;
  std::vector<DispImage>& st = steps ? *steps : own;
  st.clear();
  st.reserve(4);
  // F0, the band filter (bit 3), runs first; then F1..F3 (bits 0..2).
  st.push_back((regs.filter_enable & 8u) ? post_band_cols(in, hw, hw.band_k, threads) : post_bypass(in, hw));
  for (int n = 0; n < 3; ++n) {
    if (regs.filter_enable & (1u << n)) {
      // F1 5 x 1, F2 3 x 3, F3 5 x 3 (post_vmedian, post_median3, post_median53)
      const int ry = n == 1 ? 1 : 2, rx = n == 0 ? 0 : 1;
      DispImage next = post_rank_rows(st.back(), hw, ry, rx, (2 * ry + 1) * (2 * rx + 1) / 2, threads);
      st.push_back(std::move(next));
    } else {
      st.push_back(post_bypass(st.back(), hw));
    }
  }
  return steps ? st.back() : std::move(st.back());
}

namespace {
struct Stats {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  uint32_t count = 0, sum = 0;
  unsigned maxd = 0;
  bool alive = false;
};
void add_pixel(Stats& s, int x, int y, unsigned d) {
  s.x0 = std::min(s.x0, x);
  s.y0 = std::min(s.y0, y);
  s.x1 = std::max(s.x1, x);
  s.y1 = std::max(s.y1, y);
  s.count += 1;
  s.sum += d;
  s.maxd = std::max(s.maxd, d);
}
void fold_stats(Stats& s, Stats& a) {  // a is absorbed into s
  s.x0 = std::min(s.x0, a.x0);
  s.y0 = std::min(s.y0, a.y0);
  s.x1 = std::max(s.x1, a.x1);
  s.y1 = std::max(s.y1, a.y1);
  s.count += a.count;
  s.sum += a.sum;
  s.maxd = std::max(s.maxd, a.maxd);
  a.alive = false;
}

// The label table of section 8 as sm_objects keeps it: the flat equivalence table, the
// statistics, and the bookkeeping that recycles labels within the frame.
struct LabelTable {
  explicit LabelTable(int slots) : parent(slots, 0), st(slots), busy(slots, 0), ucur(slots, 0), uprev(slots, 0) {
    busy_list.reserve(static_cast<size_t>(slots));
    freed.reserve(static_cast<size_t>(slots));
    cand_list.reserve(static_cast<size_t>(slots));
    in_cand.assign(static_cast<size_t>(slots), 0);
  }
  std::vector<int> parent;  // root of each busy label
  std::vector<Stats> st;
  std::vector<uint8_t> busy;   // allocated and not yet freed
  std::vector<uint8_t> ucur;   // written into the row buffer on this row, before the last pixel
  std::vector<uint8_t> uprev;  // ... on the previous row
  int cand = 0;                // the label a new component gets
  bool cand_ok = true;         // ... exists (false: every label busy)
  int used = 0;                // labels 0..used-1 were allocated in this frame (the scan's range)
  int n_busy = 0;              // busy labels (diagnostics)
  bool last_near = false;      // the previous pixel was labelled ...
  int last_lab = 0;            // ... with this label
  // Speed only (the same sets as the flags above): the busy labels in any order, so the
  // per-pixel scan visits the few busy labels instead of every slot, and the labels
  // free_mask chose for the pixel.
  std::vector<int> busy_list;
  std::vector<int> freed;
  // Speed only: the busy labels that are absorbed or below min_pixels (in any order), the
  // only ones free_mask can free; a finished large component stays busy to the end of the
  // frame and is no longer visited at every pixel. Kept by classify.
  std::vector<int> cand_list;
  std::vector<uint8_t> in_cand;
};

// Puts label l in t.cand_list or takes it out after its busy flag, root or count changed.
void classify(LabelTable& t, int l, unsigned min_pixels) {
  const bool c = t.busy[l] && (t.parent[l] != l || t.st[l].count < min_pixels);
  if (c == (t.in_cand[l] != 0)) return;
  t.in_cand[l] = c;
  if (c)
    t.cand_list.push_back(l);
  else
    t.cand_list.erase(std::find(t.cand_list.begin(), t.cand_list.end(), l));
}

// Labels freed before a pixel (into t.freed): busy, not written into the row buffer on
// this row or the previous one (so no pixel still to be labelled can name them), and
// either absorbed by a merge or the root of a component that has ended smaller than
// min_pixels.
void free_mask(LabelTable& t, unsigned min_pixels) {
  t.freed.clear();
  for (const int l : t.cand_list) {  // (the other busy labels are not absorbed nor small)
    const bool referenced = t.ucur[l] || t.uprev[l] || (t.last_near && t.last_lab == l);
    const bool absorbed = t.parent[l] != l;
    if (!referenced && (absorbed || t.st[l].count < min_pixels)) t.freed.push_back(l);
  }
}

// After a pixel: choose the next candidate from the table as it was before the pixel
// (the lowest free label other than the candidate, taken when the candidate was
// allocated or none was free: the pixel's only change to busy is the candidate's
// allocation, which the choice skips anyway), then apply the frees and move the
// row-buffer marks.
void advance(LabelTable& t, bool sol, bool alloc, unsigned min_pixels) {
  const int n = static_cast<int>(t.busy.size());
  if (alloc || !t.cand_ok) {
    int c = -1;
    for (int l = 0; l < n && c < 0; ++l)
      if (!t.busy[l] && !(t.cand_ok && l == t.cand)) c = l;
    t.cand_ok = c >= 0;
    t.cand = std::max(c, 0);
  }
  for (const int l : t.freed) {
    t.busy[l] = 0;
    --t.n_busy;
    t.busy_list.erase(std::find(t.busy_list.begin(), t.busy_list.end(), l));
    classify(t, l, min_pixels);
  }
  if (sol) {
    t.uprev = t.ucur;
    std::fill(t.ucur.begin(), t.ucur.end(), 0);
    if (t.last_near) t.uprev[t.last_lab] = 1;
  } else if (t.last_near) {
    t.ucur[t.last_lab] = 1;
  }
}
}  // namespace

// The labeller's state between rows: the label table, the row buffer (previous row) and
// the left neighbour, as the hardware keeps them.
struct ObjectLabeller::State {
  const Regs& regs;
  const HwConfig& hw;
  unsigned dmask;
  ObjectList res;
  LabelTable t;
  std::vector<uint8_t> up_near;
  std::vector<unsigned> up_d;
  std::vector<int> up_lab;
  unsigned l_d = 0;
  State(int w, const Regs& r, const HwConfig& h)
      : regs(r),
        hw(h),
        dmask((1u << clog2(h.disp)) - 1),
        t(h.label_slots),
        up_near(static_cast<size_t>(w), 0),
        up_d(static_cast<size_t>(w), 0),
        up_lab(static_cast<size_t>(w), 0) {}
  void row(const DispPix* in, int y);
  ObjectList finish();
};

ObjectLabeller::ObjectLabeller(int w, const Regs& regs, const HwConfig& hw)
    : s_(std::make_unique<State>(w, regs, hw)) {}
ObjectLabeller::~ObjectLabeller() = default;
void ObjectLabeller::row(const DispPix* px, int y) { s_->row(px, y); }
ObjectList ObjectLabeller::finish() { return s_->finish(); }

void ObjectLabeller::State::row(const DispPix* in, int y) {
  const int w = static_cast<int>(up_near.size());
  for (int x = 0; x < w; ++x) {
    const DispPix p = in[x];
    const unsigned d = p & dmask;
    bool near = disp_valid(p) && d >= regs.obj_near;  // an invalid pixel is never near
    // Speed only: a pixel that is not near, after one that was not near either in the same
    // row (not its first pixel), with a free candidate label changes nothing but the row
    // buffer: the previous pixel saw the same table (no pixel changed a label since, and
    // the row-buffer marks were as now) and freed what could be freed, and advance
    // neither allocates, scans nor marks.
    if (!near && x >= 2 && !t.last_near && t.cand_ok) {
      up_near[x] = 0;
      up_d[x] = d;
      up_lab[x] = 0;
      t.last_lab = 0;
      l_d = d;
      continue;
    }
    free_mask(t, regs.obj_min_pixels);
    bool alloc = false;
    int lab = 0;
    if (near) {
      auto close = [&](unsigned e) {
        return static_cast<unsigned>(std::abs(static_cast<int>(d) - static_cast<int>(e))) <= regs.obj_tol;
      };
      const bool uok = y > 0 && up_near[x] && close(up_d[x]);
      const bool lok = x > 0 && t.last_near && close(l_d);
      const int ur = t.parent[up_lab[x]];
      const int lr = t.last_lab;
      if (uok && lok && ur != lr) {
        const int s = std::min(ur, lr), a = std::max(ur, lr);
        for (int& q : t.parent)
          if (q == a) q = s;
        fold_stats(t.st[s], t.st[a]);
        add_pixel(t.st[s], x, y, d);
        classify(t, s, regs.obj_min_pixels);
        classify(t, a, regs.obj_min_pixels);
        lab = s;
      } else if (uok || lok) {
        lab = uok ? ur : lr;
        add_pixel(t.st[lab], x, y, d);
        classify(t, lab, regs.obj_min_pixels);
      } else if (t.cand_ok) {
        lab = t.cand;
        alloc = true;
        t.parent[lab] = lab;
        t.busy[lab] = 1;
        t.busy_list.push_back(lab);
        ++t.n_busy;
        ++res.labels_started;
        t.used = std::max(t.used, lab + 1);
        t.st[lab] = Stats{x, y, x, y, 1, d, d, true};
        classify(t, lab, regs.obj_min_pixels);
      } else {
        res.table_full = true;  // no free label: the pixel is dropped (background)
        near = false;
      }
    }
    res.labels_peak = std::max(res.labels_peak, t.n_busy);
    advance(t, x == 0, alloc, regs.obj_min_pixels);
    up_near[x] = near;
    up_d[x] = d;
    up_lab[x] = lab;
    t.last_near = near;
    t.last_lab = lab;
    l_d = d;
  }
}

ObjectList ObjectLabeller::State::finish() {
  for (int i = 0; i < t.used; ++i) {
    const Stats& s = t.st[i];
    if (!s.alive || s.count < regs.obj_min_pixels) continue;
    if (static_cast<int>(res.objects.size()) >= hw.max_objects) {
      res.too_many_objects = true;
      continue;
    }
    Object o;
    o.x0 = static_cast<uint16_t>(s.x0);
    o.y0 = static_cast<uint16_t>(s.y0);
    o.x1 = static_cast<uint16_t>(s.x1);
    o.y1 = static_cast<uint16_t>(s.y1);
    o.count = s.count;
    o.sum_disp = s.sum;
    o.mean_disp = static_cast<uint8_t>(s.sum / s.count);
    o.max_disp = static_cast<uint8_t>(s.maxd);
    res.objects.push_back(o);
  }
  return res;
}

ObjectList separate_objects(const DispImage& in, const Regs& regs, const HwConfig& hw) {
  ObjectLabeller lab(in.w, regs, hw);
  for (int y = 0; y < in.h; ++y) lab.row(&in.at(0, y), y);
  return lab.finish();
}

std::vector<uint32_t> object_packet(const ObjectList& list, bool lost) {
  std::vector<uint32_t> w;
  w.push_back(0xA5000000u | (lost ? 0x400u : 0u) | (list.table_full ? 0x200u : 0u) |
              (list.too_many_objects ? 0x100u : 0u) | static_cast<uint32_t>(list.objects.size()));
  for (const Object& o : list.objects) {
    w.push_back(static_cast<uint32_t>(o.y0) << 16 | o.x0);
    w.push_back(static_cast<uint32_t>(o.y1) << 16 | o.x1);
    w.push_back(o.count);
    w.push_back(o.sum_disp);
    w.push_back(static_cast<uint32_t>(o.max_disp) << 8 | o.mean_disp);
  }
  return w;
}

}  // namespace sm
