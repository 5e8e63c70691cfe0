#include "float_ref.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "aggregate.hpp"
#include "census.hpp"
#include "dp.hpp"
#include "post.hpp"
#include "smooth.hpp"

namespace sm::fref {

const std::vector<std::string>& simplify_names() {
  static const std::vector<std::string> n = {"shift",         "wquant",     "table",       "nospatial", "round",
                                             "census-border", "agg-border", "int-penalty", "frac-q4"};
  return n;
}

namespace {
bool* field(Simplify& s, size_t i) {
  bool* f[] = {&s.cost_shift,    &s.weight_quant, &s.weight_table, &s.no_spatial, &s.norm_round,
               &s.census_border, &s.agg_border,   &s.int_penalty,  &s.frac_q4};
  return f[i];
}
}  // namespace

Simplify parse_simplify(const std::string& list) {
  if (("," + list + ",").find(",,") != std::string::npos)
    throw std::invalid_argument(fmt::format("--simplify: '{}': an empty item in a ','-separated list", list));
  Simplify s;
  std::stringstream ss(list);
  std::string item;
  const auto& names = simplify_names();
  while (std::getline(ss, item, ',')) {
    if (item == "none") continue;
    if (item == "all") {
      s = Simplify::all();
      continue;
    }
    const auto it = std::find(names.begin(), names.end(), item);
    if (it == names.end())
      throw std::invalid_argument(
          fmt::format("--simplify: unknown '{}' (known: {}, all, none)", item, fmt::join(names, ", ")));
    *field(s, static_cast<size_t>(it - names.begin())) = true;
  }
  return s;
}

std::string simplify_string(const Simplify& s) {
  Simplify c = s;
  std::vector<std::string> on;
  for (size_t i = 0; i < simplify_names().size(); ++i)
    if (*field(c, i)) on.push_back(simplify_names()[i]);
  return on.empty() ? "none" : fmt::format("{}", fmt::join(on, ","));
}

Post parse_post(const std::string& s) {
  if (s == "none") return Post::none;
  if (s == "chain") return Post::chain;
  if (s == "med5x5") return Post::med5x5;
  throw std::invalid_argument(fmt::format("--post: unknown '{}' (none, chain, med5x5)", s));
}

Params Params::defaults() {
  const HwConfig hw;
  Params p;
  p.census = hw.census;
  p.sw = hw.sw;
  p.levels = hw.disp;
  p.cost_shift = hw.cost_shift;
  p.ad_shift = hw.ad_shift;
  p.ad_max = hw.ad_max;
  p.sw_table = Regs::defaults(hw).sw_table;
  p.smooth_t = Regs::defaults(hw).smooth_t / 16.0;
  return p;
}

std::array<uint8_t, 32> fitted_table(double gc) {
  std::array<uint8_t, 32> t{};
  for (int k = 0; k < 32; ++k) {
    const double q = 4.0 * std::exp(-8.0 * k / gc);
    t[static_cast<size_t>(k)] = q >= 2 * std::sqrt(2.0) ? 3 : q >= std::sqrt(2.0) ? 2 : q >= std::sqrt(0.5) ? 1 : 0;
  }
  return t;
}

CensusImage census(const Image8& in, int side, bool zero_border) {
  if (side < 3 || side > 15 || side % 2 == 0)
    throw std::invalid_argument(fmt::format("census {} must be odd, 3..15", side));
  const int r = (side - 1) / 2, w = in.w, h = in.h;
  CensusImage out(w, h, CensusVec{0, 0, 0, 0});
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const uint8_t c = in.at(x, y);
      CensusVec v{0, 0, 0, 0};
      int k = 0;
      for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx) {
          if (dx == 0 && dy == 0) continue;
          const int xx = x + dx, yy = y + dy;
          const bool inside = xx >= 0 && xx < w && yy >= 0 && yy < h;
          bool bit = false;
          if (inside)
            bit = in.at(xx, yy) < c;
          else if (!zero_border)
            bit = in.at(std::clamp(xx, 0, w - 1), std::clamp(yy, 0, h - 1)) < c;
          if (bit) v[static_cast<size_t>(k >> 6)] |= uint64_t{1} << (k & 63);
          ++k;
        }
      out.at(x, y) = v;
    }
  return out;
}

CostVol aggregate(const Image8& left, const Image8& right, const Params& p) {
  if (left.w != right.w || left.h != right.h || left.w < 1 || left.h < 1)
    throw std::invalid_argument(
        fmt::format("float_ref: left {}x{} and right {}x{} differ", left.w, left.h, right.w, right.h));
  if (p.levels < 1 || p.levels > 256) throw std::invalid_argument(fmt::format("levels {} outside 1..256", p.levels));
  if (p.sw < 1 || p.sw > 7 || p.sw % 2 == 0) throw std::invalid_argument(fmt::format("sw {} must be odd, 1..7", p.sw));
  if (p.cost_shift < 0 || p.cost_shift > 4)
    throw std::invalid_argument(fmt::format("cost_shift {} outside 0..4", p.cost_shift));
  if (p.ad_shift < 0 || p.ad_shift > 7 || p.ad_max < 0 || p.ad_max > 15)
    throw std::invalid_argument(
        fmt::format("ad_shift {} outside 0..7 or ad_max {} outside 0..15", p.ad_shift, p.ad_max));
  if (!(p.gc > 0) || !(p.gp > 0)) throw std::invalid_argument("gc and gp must be positive");
  const Simplify& s = p.simp;
  const int w = left.w, h = left.h, nd = p.levels, r = (p.sw - 1) / 2;
  const int shift = s.cost_shift ? p.cost_shift : 0;
  const int cb = p.census * p.census - 1;

  // C(x, y, d): the Hamming cost plus the intensity term at the aggregation's scale, capped
  // at CB (CB where x - d < 0; model/census.hpp matching_cost), shifted when simp.cost_shift.
  // The term is the model's integer: it is part of the cost's definition, like the census bits.
  const CensusImage cl = census(left, p.census, s.census_border), cr = census(right, p.census, s.census_border);
  std::vector<float> c(static_cast<size_t>(w) * h * nd);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* o = &c[(static_cast<size_t>(y) * w + x) * nd];
      for (int d = 0; d < nd; ++d) {
        const int hc =
            x - d >= 0
                ? std::min(census_distance(cl.at(x, y), cr.at(x - d, y)) +
                               (ad_term(left.at(x, y), right.at(x - d, y), p.ad_shift, p.ad_max) << p.cost_shift),
                           cb)
                : cb;
        o[d] = static_cast<float>(hc >> shift);
      }
    }

  // Weight factors: intensity by |dI| (0..255), spatial by window position.
  const bool quant = s.weight_quant || s.weight_table;
  const std::array<uint8_t, 32> table = s.weight_table ? p.sw_table : fitted_table(p.gc);
  std::array<double, 256> wi{};
  for (int k = 0; k < 256; ++k)
    wi[static_cast<size_t>(k)] = quant ? static_cast<double>(sw_weight(table, k)) : std::exp(-k / p.gc);
  const int side = 2 * r + 1;
  std::vector<double> ws(static_cast<size_t>(side) * side);
  for (int j = -r; j <= r; ++j)
    for (int i = -r; i <= r; ++i)
      ws[static_cast<size_t>((j + r) * side + i + r)] = s.no_spatial ? 1.0 : std::exp(-std::sqrt(i * i + j * j) / p.gp);
  const bool integer = s.integer_weights();
  // 2^CW - 1 with CW = clog2((CB >> shift) + 1): the model's saturation (never reached).
  uint32_t sat = 1;
  while (sat < static_cast<uint32_t>((cb >> shift) + 1)) sat <<= 1;
  sat -= 1;

  CostVol out;
  out.w = w;
  out.h = h;
  out.d = nd;
  out.unit = static_cast<double>(1 << shift);
  out.a.assign(c.size(), 0.0f);
  std::vector<double> acc(static_cast<size_t>(nd));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::fill(acc.begin(), acc.end(), 0.0);
      double wsum = 0;
      const int ip = left.at(x, y);
      for (int j = -r; j <= r; ++j)
        for (int i = -r; i <= r; ++i) {
          int xx = x + i, yy = y + j;
          if (xx < 0 || xx >= w || yy < 0 || yy >= h) {
            if (s.agg_border) continue;  // weight 0
            xx = std::clamp(xx, 0, w - 1);
            yy = std::clamp(yy, 0, h - 1);
          }
          const double wt =
              wi[static_cast<size_t>(std::abs(left.at(xx, yy) - ip))] * ws[static_cast<size_t>((j + r) * side + i + r)];
          if (wt == 0) continue;
          wsum += wt;
          const float* q = &c[(static_cast<size_t>(yy) * w + xx) * nd];
          for (int d = 0; d < nd; ++d) acc[static_cast<size_t>(d)] += wt * q[d];
        }
      float* o = &out.a[(static_cast<size_t>(y) * w + x) * nd];
      if (wsum == 0) continue;  // every weight 0: A = 0 (as the model)
      if (s.norm_round && integer) {
        // The model's normalisation: sums of integers below 2^53 are exact in double.
        const uint32_t rec = sw_recip(static_cast<uint32_t>(wsum));
        for (int d = 0; d < nd; ++d) {
          const auto raw = static_cast<uint64_t>(acc[static_cast<size_t>(d)]);
          const uint64_t v = (raw * rec + (1u << (kRecipShift - 1))) >> kRecipShift;
          o[d] = static_cast<float>(std::min<uint64_t>(v, sat));
        }
      } else if (s.norm_round) {
        for (int d = 0; d < nd; ++d) o[d] = static_cast<float>(std::floor(acc[static_cast<size_t>(d)] / wsum + 0.5));
      } else {
        for (int d = 0; d < nd; ++d) o[d] = static_cast<float>(acc[static_cast<size_t>(d)] / wsum);
      }
    }
  return out;
}

double dp_penalty(double penalty_raw, const CostVol& a, const Params& p) {
  const double u = penalty_raw / a.unit;
  return p.simp.int_penalty ? std::clamp(std::floor(u + 0.5), 0.0, 255.0) : u;
}

std::vector<int> trellis_line(const float* a, int n, int levels, double occ) {
  const double inf = std::numeric_limits<double>::infinity();
  const int nd = levels, sites = 2 * n;
  std::vector<double> u(static_cast<size_t>(nd), inf), un(static_cast<size_t>(nd));
  std::vector<uint8_t> dec(static_cast<size_t>(sites + 1) * nd, 0);
  u[0] = 0;  // U(0, 0) = 0, U(0, d > 0) unreachable
  for (int i = 1; i <= sites; ++i) {
    uint8_t* di = &dec[static_cast<size_t>(i) * nd];
    for (int d = 0; d < nd; ++d) {
      const size_t k = static_cast<size_t>(d);
      if ((i + d) & 1) {  // matched node: xl = (i-1+d)/2 (xl >= n never reaches the end: cost 0)
        const int xl = (i - 1 + d) / 2;
        un[k] = u[k] + (xl < n ? static_cast<double>(a[static_cast<size_t>(xl) * nd + d]) : 0.0);
      } else {  // occlusion node: the first of choice 0, 1, 2 reaching the minimum
        double b = u[k];
        uint8_t ch = 0;
        if (d >= 1 && u[k - 1] + occ < b) {
          b = u[k - 1] + occ;
          ch = 1;
        }
        if (d + 1 < nd && u[k + 1] + occ < b) {
          b = u[k + 1] + occ;
          ch = 2;
        }
        un[k] = b;
        di[d] = ch;
      }
    }
    std::swap(u, un);
  }
  std::vector<int> match(static_cast<size_t>(n), -1);
  int d = 0;
  for (int i = sites; i >= 1; --i) {
    if ((i + d) & 1) {
      match[static_cast<size_t>((i - 1 + d) / 2)] = d;
    } else {
      const uint8_t ch = dec[static_cast<size_t>(i) * nd + d];
      d += ch == 1 ? -1 : ch == 2 ? 1 : 0;
    }
  }
  return match;
}

DispImage trellis(const CostVol& a, double penalty_raw, const Params& p) {
  const double occ = dp_penalty(penalty_raw, a, p);
  DispImage out(a.w, a.h);
  std::vector<DispPix> line;
  for (int y = 0; y < a.h; ++y) {
    dp_fill(trellis_line(a.pix(0, y), a.w, a.d, occ), line);
    std::copy(line.begin(), line.end(), &out.at(0, y));
  }
  return out;
}

DispImage post(const DispImage& dp, const Params& p) {
  HwConfig hw;
  hw.disp = p.levels;
  switch (p.post) {
    case Post::chain: {
      Regs regs = Regs::defaults(hw);
      regs.filter_enable = 15;  // F0 (band, hw.band_k) and F1..F3
      return post_process(dp, regs, hw);
    }
    case Post::med5x5:
      return post_median(dp, hw, 2, 2);
    case Post::none:
      break;
  }
  return dp;
}

namespace {

// Offset of the parabola's minimum through (-1, cm), (0, c0), (1, cp), in levels.
double fit_parabola(double cm, double c0, double cp, bool q4) {
  const double num = cm - cp, den = 2 * (cm - 2 * c0 + cp);
  if (!(den > 0)) return 0;
  if (!q4) return std::clamp(num / den, -0.5, 0.5);
  const double q = std::min(8.0, std::floor(16 * std::fabs(num) / den + 0.5));  // half away from zero
  return (num < 0 ? -q : q) / 16;
}

// The lowest level of least cost.
int wta(const float* c, int nd) { return static_cast<int>(std::min_element(c, c + nd) - c); }

}  // namespace

std::vector<float> subpix(const CostVol& a, const DispImage& dp, const DispImage& out, const Params& p) {
  std::vector<float> v(static_cast<size_t>(a.w) * a.h);
  for (int y = 0; y < a.h; ++y)
    for (int x = 0; x < a.w; ++x) {
      const int d = static_cast<int>(disp_value(dp.at(x, y))), o = static_cast<int>(disp_value(out.at(x, y)));
      const float* c = a.pix(x, y);
      double f = 0;
      if (o == d && d > 0 && d < a.d - 1 && std::abs(wta(c, a.d) - d) <= 1)
        f = fit_parabola(c[d - 1], c[d], c[d + 1], p.simp.frac_q4);
      v[static_cast<size_t>(y) * a.w + x] = static_cast<float>(o + f);
    }
  return v;
}

std::vector<float> smooth(const std::vector<float>& v, int w, int h, const Params& p) {
  if (p.smooth_t <= 0) return v;
  std::vector<float> o(v.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double c = v[static_cast<size_t>(y) * w + x];
      double s = 0;
      int k = 0;
      for (int yy = std::max(0, y - kSmoothR); yy <= std::min(h - 1, y + kSmoothR); ++yy)
        for (int xx = std::max(0, x - kSmoothR); xx <= std::min(w - 1, x + kSmoothR); ++xx) {
          const double d = v[static_cast<size_t>(yy) * w + xx] - c;
          if (std::abs(d) <= p.smooth_t) s += d, ++k;
        }
      // the rounded Q.4 value: the mean's offset in 1/16 px, floor(16 s / k + 1/2)
      const double off = p.simp.frac_q4 ? std::floor(16 * s / k + 0.5) / 16 : s / k;
      o[static_cast<size_t>(y) * w + x] = static_cast<float>(c + off);
    }
  return o;
}

DispImage run(const Image8& left, const Image8& right, const Params& p, double penalty_raw) {
  return post(trellis(aggregate(left, right, p), penalty_raw, p), p);
}

}  // namespace sm::fref
