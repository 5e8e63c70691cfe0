// Floating-point reference of the pipeline (issue 21): the algorithm of
// docs/algorithm.md sections 3-7 (census, Hamming cost, support-weight aggregation,
// centre-referenced trellis DP, post filters) with real-valued support weights
// exp(-|dI|/gc - dist/gp), unquantized costs and a real occlusion penalty, for
// measuring what each fixed-point simplification of the bit-exact model (model/) costs.
// Every simplification can be switched on by itself (Simplify); with all of them on the
// result equals the bit-exact model (run_pipeline at identity brightness and
// rectification). Not part of the IP and not used by the model; docs/evaluation.md,
// "What each fixed-point simplification costs".
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "sm_types.hpp"

namespace sm::fref {

// The bit-exact model's simplifications, each on its own (false = the float algorithm).
struct Simplify {
  bool cost_shift = false;     // C = H >> cost_shift (floor) instead of H
  bool weight_quant = false;   // intensity weight: a 2-bit code of |dI| >> 3 (weight 0, 1, 2, 4),
                               // the codes fitted to exp(-|dI|/gc) (fitted_table)
  bool weight_table = false;   // intensity weight: the model's sw_table codes (Params::sw_table);
                               // implies the quantization
  bool no_spatial = false;     // drop the spatial term exp(-dist/gp)
  bool norm_round = false;     // A rounded to an integer: the model's RECIP formula when the
                               // weights are integers, else round to nearest
  bool census_border = false;  // census: a neighbour outside the image gives bit 0 (the
                               // model before issue 21; not in all()); off: the nearest
                               // pixel inside (clamped coordinates, the model)
  bool agg_border = false;     // aggregation: a neighbour outside the image has weight 0
                               // (model); off: clamped coordinates
  bool int_penalty = false;    // occlusion penalty: an integer 0..255 in the units of A
                               // (the model's 8-bit occ register)
  bool frac_q4 = false;        // sub-pixel fraction rounded to 1/16 (the model's fit_q4);
                               // off: the real-valued fit
  static Simplify none() { return {}; }
  // Every simplification the bit-exact model makes.
  static Simplify all() { return {true, true, true, true, true, false, true, true, true}; }
  bool integer_weights() const { return (weight_quant || weight_table) && no_spatial; }
};

// Names of the switches, in the order of Simplify, for the command line and reports.
const std::vector<std::string>& simplify_names();
// "a,b,c" of simplify_names() entries, "all" or "none" (combinations add up). Throws
// std::invalid_argument naming an unknown entry or an empty item ("a,,b", "a,", "").
Simplify parse_simplify(const std::string& list);
std::string simplify_string(const Simplify& s);  // "none" or the names that are on

enum class Post { none, chain, med5x5 };
Post parse_post(const std::string& s);  // "none", "chain" (the model's F0-F3), "med5x5"

struct Params {
  int census = 15;                     // census window side (odd, 3..15)
  int sw = 5;                          // support-weight window side (odd, 1..7)
  int levels = 128;                    // disparity levels 0..levels-1
  int cost_shift = 2;                  // used when simp.cost_shift
  int ad_shift = 2;                    // the cost's intensity term (model ad_term) ...
  int ad_max = 7;                      // ... and its cap (0: census only)
  double gc = 10;                      // intensity scale of the float weights
  double gp = 10;                      // spatial scale of the float weights
  std::array<uint8_t, 32> sw_table{};  // used when simp.weight_table (model codes)
  double smooth_t = 1.5;               // smoothing threshold in pixels (the model's SMOOTH_T / 16)
  Simplify simp;
  Post post = Post::chain;
  // Model defaults for census, sw, levels, cost_shift, ad_shift, ad_max, sw_table and smooth_t
  // (HwConfig{}, Regs::defaults); gc = gp = 10 (the float twin of issue 21).
  static Params defaults();
};

// The 2-bit codes of |dI| >> 3 nearest (in log2) to exp(-|dI|/gc) with bin 0 at weight 4:
// code of bin k from q = 4 exp(-8k/gc): 3 if q >= 2 sqrt 2, 2 if q >= sqrt 2, 1 if
// q >= 1/sqrt 2, else 0. (gc = 10: 3, 2, 1, 0, 0, ...)
std::array<uint8_t, 32> fitted_table(double gc);

// Aggregated costs A(x, y, d), d fastest, in the units of the cost the aggregation sums:
// 1 raw Hamming count, or 2^cost_shift counts when simp.cost_shift.
struct CostVol {
  int w = 0, h = 0, d = 0;
  double unit = 1;       // raw Hamming counts per unit of A
  std::vector<float> a;  // w * h * d
  const float* pix(int x, int y) const { return &a[(static_cast<size_t>(y) * w + x) * d]; }
};

// Census vectors with the chosen border rule (bit order of census_transform).
CensusImage census(const Image8& in, int side, bool zero_border);
// Census, Hamming cost and aggregation; left/right of the same size. Throws
// std::invalid_argument on bad sizes or parameters.
CostVol aggregate(const Image8& left, const Image8& right, const Params& p);

// The occlusion penalty the DP uses, in units of A, for a penalty on the raw Hamming
// scale (penalty_raw / unit; rounded and clamped to 0..255 when simp.int_penalty).
double dp_penalty(double penalty_raw, const CostVol& a, const Params& p);

// Trellis DP of one line (the recurrence, tie order and backward pass of trellis_line,
// in double); returns disp(xl) of the matched pixels, -1 for left-occluded ones.
std::vector<int> trellis_line(const float* a, int n, int levels, double occ);
// Every line, left-occluded pixels filled by the model's rule (dp_fill); all valid.
DispImage trellis(const CostVol& a, double penalty_raw, const Params& p);
// The post filters of p.post (the model's post_process / post_median).
DispImage post(const DispImage& dp, const Params& p);

// Sub-pixel disparity of every pixel (docs/algorithm.md 9.1, the default estimator: the
// parabola through A(d - 1), A(d), A(d + 1) at the DP's level d where the WTA level is
// within 1 of d and 0 < d < levels - 1, clamped to half a level), kept where the post
// filters kept d (`out` = post(dp)); else the output's level. Real-valued, or the model's
// Q.4 value with simp.frac_q4 (equal to the model's dense output on integer costs).
std::vector<float> subpix(const CostVol& a, const DispImage& dp, const DispImage& out, const Params& p);

// The sub-pixel output smoothed (docs/algorithm.md 9.7): every pixel of v (w x h, all valid)
// becomes the mean of the pixels of its 5x5 window inside the image within p.smooth_t of it
// (0: v unchanged). Real-valued, or rounded to 1/16 with simp.frac_q4 (the values then
// Q.4 already: the model's smooth_output).
std::vector<float> smooth(const std::vector<float>& v, int w, int h, const Params& p);

// Whole pipeline for one penalty (raw Hamming scale).
DispImage run(const Image8& left, const Image8& right, const Params& p, double penalty_raw);

}  // namespace sm::fref
