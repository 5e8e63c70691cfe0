#include "post.hpp"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

namespace sm {

namespace {
int clog2(long v) {  // as Verilog's $clog2
  int n = 0;
  while ((1L << n) < v) ++n;
  return n;
}
}  // namespace

DispImage post_median(const DispImage& in, const HwConfig& hw, int ry, int rx) {
  return post_rank(in, hw, ry, rx, (2 * ry + 1) * (2 * rx + 1) / 2);
}

DispImage post_rank(const DispImage& in, const HwConfig& hw, int ry, int rx, int rank) {
  const unsigned dmask = (1u << clog2(hw.disp)) - 1;
  auto key = [&](DispPix p) -> unsigned { return disp_valid(p) ? (p & dmask) + 1 : 0; };
  DispImage out(in.w, in.h);
  std::vector<unsigned> win;
  const int n = (2 * ry + 1) * (2 * rx + 1);
  if (rank < 0 || rank >= n) throw std::invalid_argument("post_rank: rank outside the window");
  win.reserve(n);
  for (int y = 0; y < in.h; ++y)
    for (int x = 0; x < in.w; ++x) {
      const unsigned c = key(in.at(x, y));
      win.clear();
      for (int j = -ry; j <= ry; ++j)
        for (int i = -rx; i <= rx; ++i) {
          const int xx = x + i, yy = y + j;
          const bool inside = xx >= 0 && xx < in.w && yy >= 0 && yy < in.h;
          win.push_back(inside ? key(in.at(xx, yy)) : c);
        }
      std::nth_element(win.begin(), win.begin() + rank, win.end());
      const unsigned m = win[rank];
      out.at(x, y) = m == 0 ? DispPix{0} : make_disp(m - 1, true);
    }
  return out;
}

DispImage post_vmedian(const DispImage& in, const HwConfig& hw) {
  return post_median(in, hw, 2, 0);
}
DispImage post_median3(const DispImage& in, const HwConfig& hw) {
  return post_median(in, hw, 1, 1);
}
DispImage post_median53(const DispImage& in, const HwConfig& hw) {
  return post_median(in, hw, 2, 1);
}

DispImage post_process(const DispImage& in, const Regs& regs, const HwConfig& hw,
                       std::vector<DispImage>* steps) {
  DispImage cur = in;
  if (steps) steps->clear();
  for (int n = 0; n < 3; ++n) {
    if (regs.filter_enable & (1u << n)) {
      if (n == 0) cur = post_vmedian(cur, hw);
      if (n == 1) cur = post_median3(cur, hw);
      if (n == 2) cur = post_median53(cur, hw);
    }
    if (steps) steps->push_back(cur);
  }
  return cur;
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
}  // namespace

ObjectList separate_objects(const DispImage& in, const Regs& regs, const HwConfig& hw) {
  const unsigned dmask = (1u << clog2(hw.disp)) - 1;
  const int slots = hw.label_slots;
  ObjectList res;
  std::vector<int> parent(slots);
  for (int i = 0; i < slots; ++i) parent[i] = i;
  std::vector<Stats> st(slots);
  int next = 0;
  // The row buffer (previous row) and the left neighbour, as the hardware keeps them.
  std::vector<uint8_t> up_near(in.w, 0);
  std::vector<unsigned> up_d(in.w, 0);
  std::vector<int> up_lab(in.w, 0);
  bool l_near = false;
  unsigned l_d = 0;
  int l_lab = 0;
  for (int y = 0; y < in.h; ++y)
    for (int x = 0; x < in.w; ++x) {
      const DispPix p = in.at(x, y);
      const unsigned d = p & dmask;
      bool near = disp_valid(p) && d >= regs.obj_near;
      int lab = 0;
      if (near) {
        const bool uok =
            y > 0 && up_near[x] &&
            static_cast<unsigned>(std::abs(static_cast<int>(d) - static_cast<int>(up_d[x]))) <=
                regs.obj_tol;
        const bool lok = x > 0 && l_near &&
                         static_cast<unsigned>(
                             std::abs(static_cast<int>(d) - static_cast<int>(l_d))) <= regs.obj_tol;
        const int ur = parent[up_lab[x]];
        const int lr = l_lab;
        if (uok && lok && ur != lr) {
          const int s = std::min(ur, lr), a = std::max(ur, lr);
          for (int i = 0; i < slots; ++i)
            if (parent[i] == a) parent[i] = s;
          Stats& S = st[s];
          const Stats& A = st[a];
          S.x0 = std::min(S.x0, A.x0);
          S.y0 = std::min(S.y0, A.y0);
          S.x1 = std::max(S.x1, A.x1);
          S.y1 = std::max(S.y1, A.y1);
          S.count += A.count;
          S.sum += A.sum;
          S.maxd = std::max(S.maxd, A.maxd);
          st[a].alive = false;
          add_pixel(S, x, y, d);
          lab = s;
        } else if (uok || lok) {
          lab = uok ? ur : lr;
          add_pixel(st[lab], x, y, d);
        } else if (next < slots) {
          lab = next++;
          Stats& S = st[lab];
          S.x0 = S.x1 = x;
          S.y0 = S.y1 = y;
          S.count = 1;
          S.sum = d;
          S.maxd = d;
          S.alive = true;
        } else {
          res.table_full = true;  // no free label: the pixel is dropped (background)
          near = false;
        }
      }
      up_near[x] = near;
      up_d[x] = d;
      up_lab[x] = lab;
      l_near = near;
      l_d = d;
      l_lab = lab;
    }
  for (int i = 0; i < next; ++i) {
    const Stats& s = st[i];
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
