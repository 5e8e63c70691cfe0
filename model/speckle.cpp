#include "speckle.hpp"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <utility>

#include "sm_defs.hpp"

namespace sm {

namespace {

// Row numbers modulo 2^RW: a live root was reached at most ROWS + 1 rows ago.
uint8_t row_mask(int rows) {
  int m = 1;
  while (m <= rows + 1) m <<= 1;
  return static_cast<uint8_t>(m - 1);
}

constexpr uint8_t kRankMax = 15;  // ranks saturate (4 bits): a find's bound, not its result

// Sizes and counts of failing pixels saturate at kSpeckleSizeMax (13 bits).
uint16_t sat_add(uint16_t a, unsigned b) { return static_cast<uint16_t>(std::min<unsigned>(kSpeckleSizeMax, a + b)); }

bool near(uint32_t a, uint32_t b, unsigned diff) {
  return out_valid(a) && out_valid(b) &&
         static_cast<unsigned>(std::abs(static_cast<int>(out_q4(a)) - static_cast<int>(out_q4(b)))) <= diff;
}

}  // namespace

SpeckleStage::SpeckleStage(int max_width, int rows, int labels)
    : max_width_(max_width),
      rows_(rows),
      labels_(labels),
      none_(static_cast<uint16_t>(labels)),
      keep_(static_cast<uint16_t>(labels + 1)),
      row_mask_(row_mask(rows)),
      words_(static_cast<size_t>(rows + 1) * static_cast<size_t>(max_width)),
      codes_(words_.size()),
      meta_(static_cast<size_t>(rows + 1)),
      parent_(static_cast<size_t>(labels)),
      size_(parent_.size()),
      bad_(parent_.size()),
      refs_(parent_.size()),
      fifo_(parent_.size()),
      rank_(parent_.size()),
      last_(parent_.size()) {
  if (max_width < 1 || rows < 1 || rows > 126 || labels < 1 || labels > 32766)
    throw std::invalid_argument("SpeckleStage: MAX_WIDTH >= 1, ROWS 1..126, LABELS 1..32766");
  if (words_.size() + parent_.size() > 65535) throw std::invalid_argument("SpeckleStage: references above 16 bits");
}

void SpeckleStage::start_row(uint8_t side, const SpeckleRegs& regs) {
  const bool sof = (side & defs::kSideSof) != 0;
  slot_ = (slot_ + 1) % (rows_ + 1);
  row_ = static_cast<uint8_t>((row_ + 1) & row_mask_);
  if (sof) {
    fid_ = static_cast<uint8_t>((fid_ + 1) & row_mask_);
    en_ = regs.en;
    size_reg_ = regs.size;
    trust_reg_ = regs.trust;
    diff_ = regs.diff;
  }
  meta_[static_cast<size_t>(slot_)] = {(side & defs::kSideReal) != 0,
                                       sof,
                                       en_ != 0,
                                       static_cast<uint8_t>(side >> defs::kSideTagLsb & 3),
                                       fid_,
                                       size_reg_,
                                       trust_reg_};
  x_ = 0;
  started_ = true;
}

uint16_t SpeckleStage::find(uint16_t l) {
  int hops = 0;
  for (; parent_[l] != l; ++hops) l = parent_[l];
  stats_.longest_find = std::max(stats_.longest_find, hops);
  return l;
}

void SpeckleStage::add_pixel(uint16_t r, bool lr_bad) {
  size_[r] = sat_add(size_[r], 1);
  bad_[r] = sat_add(bad_[r], lr_bad);
  last_[r] = row_;
  ++refs_[r];
}

// A new region of one pixel; keep_ when no label is free.
uint16_t SpeckleStage::take_label(bool lr_bad) {
  uint16_t n = 0;
  if (fresh_ < labels_) {
    n = fresh_++;
  } else if (fifo_count_ > 0) {
    n = fifo_[fifo_head_];
    fifo_head_ = static_cast<uint16_t>((fifo_head_ + 1) % labels_);
    --fifo_count_;
  } else {
    return keep_;
  }
  parent_[n] = n;
  rank_[n] = 0;
  size_[n] = 0;
  bad_[n] = 0;
  refs_[n] = 0;
  add_pixel(n, lr_bad);
  stats_.peak_labels = std::max(stats_.peak_labels, ++in_use_);
  return n;
}

// Roots a (the upper neighbour's) and b become one; returns the survivor.
uint16_t SpeckleStage::merge(uint16_t a, uint16_t b) {
  if (rank_[b] > rank_[a]) std::swap(a, b);
  if (rank_[a] == rank_[b] && rank_[a] < kRankMax) ++rank_[a];
  parent_[b] = a;
  ++refs_[a];
  size_[a] = sat_add(size_[a], size_[b]);
  bad_[a] = sat_add(bad_[a], bad_[b]);
  return a;
}

// A decided pixel no longer holds label l; a label nothing holds is free, and no longer
// holds its parent.
void SpeckleStage::release(uint16_t l) {
  while (--refs_[l] == 0) {
    fifo_[(fifo_head_ + fifo_count_) % labels_] = l;
    ++fifo_count_;
    --in_use_;
    if (parent_[l] == l) break;
    l = parent_[l];
  }
}

// The label of the pixel entering at x_ (none_: invalid or virtual). The left neighbour's
// label is a root: it was one when given, one beat ago, and only labelling merges.
uint16_t SpeckleStage::label(uint32_t word, bool real) {
  if (!real || !out_valid(word)) return none_;
  const int up_slot = (slot_ + rows_) % (rows_ + 1);
  const bool up_j = !meta_[static_cast<size_t>(slot_)].sof && near(word, words_[at(up_slot)], diff_);
  const bool left_j = x_ > 0 && near(word, left_word_, diff_);
  const uint16_t up = up_j ? codes_[at(up_slot)] : none_, left = left_j ? left_code_ : none_;
  const bool keep = up == keep_ || left == keep_;
  const uint16_t ru = up < labels_ ? find(up) : none_;
  uint16_t r = ru != none_ ? ru : left < labels_ ? left : none_;
  if (ru != none_ && left < labels_ && ru != left) r = merge(ru, left);
  const bool lr_bad = (out_conf(word) & kConfLrOk) == 0;
  if (r == none_) return keep ? keep_ : take_label(lr_bad);
  add_pixel(r, lr_bad);
  if (keep) size_[r] = kSpeckleSizeMax;
  return r;
}

// The word the stored pixel (label code, word, its row's meta) leaves with; ended: its
// frame has no more rows to come.
uint32_t SpeckleStage::verdict(uint16_t code, uint32_t word, const RowMeta& m, bool ended) {
  if (!m.real || code == none_) return word;
  bool kept = code == keep_;
  if (!kept) {
    const uint16_t r = find(code);
    kept = (!ended && ((row_ - last_[r]) & row_mask_) <= 1) || size_[r] > m.size;
    if (!kept && size_[r] > m.trust && (static_cast<unsigned>(bad_[r]) << kSpeckleTrustShift) < size_[r]) {
      kept = true;
      stats_.trusted += m.en;
    }
    release(code);
  }
  return kept || !m.en ? word : kOutSpeckle;
}

SpeckleStage::Beat SpeckleStage::step(uint8_t side, uint32_t word, const SpeckleRegs& regs) {
  const bool real = (side & defs::kSideReal) != 0;
  if (side & defs::kSideSol)
    start_row(side, regs);
  else if (started_ && x_ < max_width_)
    ++x_;
  if (!started_ || x_ >= max_width_) return {};
  const uint16_t code = label(word, real);
  stats_.keep_pixels += code == keep_;
  words_[at(slot_)] = word;
  codes_[at(slot_)] = code;
  left_word_ = word;
  left_code_ = code;
  const int dec = (slot_ + 1) % (rows_ + 1);
  const RowMeta& m = meta_[static_cast<size_t>(dec)];
  Beat out;
  out.side = static_cast<uint8_t>((m.real ? defs::kSideReal : 0) | (x_ == 0 ? defs::kSideSol : 0) |
                                  (x_ == 0 && m.sof ? defs::kSideSof : 0) | m.tag << defs::kSideTagLsb);
  out.word = verdict(codes_[at(dec)], words_[at(dec)], m, !real || m.fid != fid_);
  return out;
}

OutImage speckle_output(const OutImage& in, const SpeckleRegs& regs, int rows, int labels, SpeckleStats* stats) {
  SpeckleStage st(std::max(1, in.w), rows, labels);
  OutImage out(in.w, in.h);
  size_t k = 0;
  auto beat = [&](uint8_t side, uint32_t word) {
    const SpeckleStage::Beat b = st.step(side, word, regs);
    if ((b.side & defs::kSideReal) && k < out.px.size()) out.px[k++] = b.word;
  };
  for (int y = 0; y < in.h; ++y)
    for (int x = 0; x < in.w; ++x)
      beat(static_cast<uint8_t>(defs::kSideReal | (x == 0 ? defs::kSideSol : 0) | (x + y == 0 ? defs::kSideSof : 0)),
           in.at(x, y));
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < in.w; ++x) beat(x == 0 ? defs::kSideSol : 0, 0);
  if (k != out.px.size()) throw std::logic_error("speckle_output: a pixel did not leave the stage");
  if (stats) *stats = st.stats();
  return out;
}

OutImage speckle_words(const OutImage& in, const Regs& regs, const HwConfig& hw) {
  if (hw.speckle_rows == 0) return in;
  return speckle_output(in, speckle_regs(regs), hw.speckle_rows, hw.speckle_labels);
}

}  // namespace sm
