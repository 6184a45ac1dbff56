// The coarse phase of the global search (see global_localiser.hpp): every
// lattice position at every heading scored on the blurred field. In a window
// each position is scored. Over the whole map the lattice is searched by
// branch and bound: blocks of 4 x 4 positions are bounded (CoarseBounds),
// the most promising first are split into quarters down to single positions,
// and a block or heading whose bound falls below the coarse_keep-th best hit
// so far is never looked at again. The hits kept are those that scoring
// every position would keep: a position's hits score at most its block's
// bound, and a hit below coarse_keep others is never kept. Scores and
// bounds are summed four at a time (SumFour over the grids laid out by
// phase, LatticeGains): the top-level blocks 2 x 2, a block's four
// quarters, a 2 x 2 block's positions.
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>

#include "structloc/localisation_core/global/global_localiser.hpp"

namespace structloc::localisation_core {

void GlobalSearch::CoarseStep() {
  if (window_) {
    if (next_ < window_positions_.size()) {
      CoarsePosition(window_positions_[next_++], scored_headings_);
    } else {
      SelectHits();
    }
    return;
  }
  const int top = g_.coarse_bounds_.Levels();
  const int side = 1 << top;
  const int top_columns = (g_.lattice_.columns + side - 1) / side;
  const size_t top_count =
      static_cast<size_t>(top_columns) * static_cast<size_t>((g_.lattice_.rows + side - 1) / side);
  if (next_top_ < top_count) {
    // Every top-level block is bounded before any is expanded, so that the
    // most promising of the whole map is expanded first; row by row, the
    // bounds computed 2 x 2 blocks at a time.
    const int top_column = static_cast<int>(next_top_ % static_cast<size_t>(top_columns));
    const int top_row = static_cast<int>(next_top_ / static_cast<size_t>(top_columns));
    if (top_bounds_.empty())
      top_bounds_.assign(2 * (static_cast<size_t>(top_columns) + 1),
                         std::vector<float>(static_cast<size_t>(headings_)));
    if (top_column % 2 == 0 && top_row % 2 == 0) {
      const size_t at = static_cast<size_t>(top_column);
      const size_t below = static_cast<size_t>(top_columns) + 1 + at;
      SumFour(
          top, top_column, top_row, scored_headings_,
          {&top_bounds_[at], &top_bounds_[at + 1], &top_bounds_[below], &top_bounds_[below + 1]});
    }
    Block block;
    block.level = top;
    block.column = top_column * side;
    block.row = top_row * side;
    ++next_top_;
    if (BlockHasPositions(block)) {
      block.first = top_headings_.size();
      BoundBlock(block, scored_headings_,
                 top_bounds_[static_cast<size_t>(top_row % 2) * (top_columns + 1) +
                             static_cast<size_t>(top_column)],
                 top_headings_);
      block.end = top_headings_.size();
      if (block.end > block.first) tops_.push_back(block);
    }
    if (next_top_ < top_count) return;
    std::sort(tops_.begin(), tops_.end(),
              [](const Block& a, const Block& b) { return a.bound < b.bound; });
    blocks_ = std::move(tops_);
    return;
  }
  if (blocks_.empty()) {
    SelectHits();
    return;
  }
  const Block block = blocks_.back();
  blocks_.pop_back();
  // A block's headings lie at the end of block_headings_ (those of the blocks
  // below it on the stack lie before them), the top level's in top_headings_.
  const bool top_level = block.level == top;
  const auto& from = top_level ? top_headings_ : block_headings_;
  const float threshold = KeepThreshold();
  expanding_.clear();
  for (size_t i = block.first; i < block.end; ++i) {
    if (from[i].bound >= threshold) expanding_.push_back(from[i].heading);
  }
  if (!top_level) block_headings_.resize(block.first);
  if (!expanding_.empty()) ExpandBlock(block);
}

void GlobalSearch::ExpandBlock(const Block& block) {
  const auto& lattice = g_.lattice_;
  const int half = 1 << (block.level - 1);
  if (block.level == 1) {
    CoarseBlock(block);
    return;
  }
  // The quarters' bounds, all four at once.
  const int below = block.level - 1;
  SumFour(below, block.column >> below, block.row >> below, expanding_,
          {&quarter_bounds_[0], &quarter_bounds_[1], &quarter_bounds_[2], &quarter_bounds_[3]});
  Block quarters[4];
  int count = 0;
  for (int q = 0; q < 4; ++q) {
    Block& quarter = quarters[count];
    quarter.level = block.level - 1;
    quarter.column = block.column + (q % 2) * half;
    quarter.row = block.row + (q / 2) * half;
    if (quarter.column >= lattice.columns || quarter.row >= lattice.rows) continue;
    if (!BlockHasPositions(quarter)) continue;
    quarter_headings_[count].clear();
    BoundBlock(quarter, expanding_, quarter_bounds_[q], quarter_headings_[count]);
    if (!quarter_headings_[count].empty()) ++count;
  }
  // The most promising quarter goes on top of the stack, so it is expanded next.
  int order[4] = {0, 1, 2, 3};
  for (int i = 1; i < count; ++i) {  // insertion sort, by bound
    for (int j = i; j > 0 && quarters[order[j]].bound < quarters[order[j - 1]].bound; --j)
      std::swap(order[j], order[j - 1]);
  }
  for (int i = 0; i < count; ++i) {
    Block quarter = quarters[order[i]];
    const auto& headings = quarter_headings_[order[i]];
    quarter.first = block_headings_.size();
    block_headings_.insert(block_headings_.end(), headings.begin(), headings.end());
    quarter.end = block_headings_.size();
    blocks_.push_back(quarter);
  }
}

bool GlobalSearch::BlockHasPositions(const Block& block) const {
  const auto& lattice = g_.lattice_;
  const int side = 1 << block.level;
  const size_t stride = static_cast<size_t>(lattice.columns) + 1;
  const size_t i0 = static_cast<size_t>(block.column), j0 = static_cast<size_t>(block.row);
  const size_t i1 = static_cast<size_t>(std::min(block.column + side, lattice.columns));
  const size_t j1 = static_cast<size_t>(std::min(block.row + side, lattice.rows));
  const auto& before = lattice.positions_before;
  return before[j1 * stride + i1] - before[j0 * stride + i1] - before[j1 * stride + i0] +
             before[j0 * stride + i0] >
         0;
}

void GlobalSearch::SumFour(int level, int column, int row, const std::vector<uint16_t>& headings,
                           const std::array<std::vector<float>*, 4>& out) const {
  const size_t n = coarse_count_;
  const LatticeGains& gains = g_.phase_gains_[static_cast<size_t>(level)];
  const LatticeGains::Offset* prepared = phase_offsets_[static_cast<size_t>(level)].data();
  float* const sums_out[4] = {out[0]->data(), out[1]->data(), out[2]->data(), out[3]->data()};
  for (const uint16_t h : headings) {
    const LatticeGains::Offset* offsets = prepared + static_cast<size_t>(h) * n;
    uint32_t sums[4] = {0, 0, 0, 0};
    for (size_t i = 0; i < n; ++i) gains.AddBlock(offsets[i], column, row, sums);
    for (int q = 0; q < 4; ++q) sums_out[q][h] = static_cast<float>(sums[q]);
  }
}

void GlobalSearch::BoundBlock(Block& block, const std::vector<uint16_t>& headings,
                              const std::vector<float>& bounds, std::vector<BoundedHeading>& out) {
  const float threshold = KeepThreshold();
  block.bound = -std::numeric_limits<float>::infinity();
  for (const uint16_t h : headings) {
    const float bound = bounds[h];
    work_ += coarse_count_;
    if (bound < threshold) continue;
    out.push_back({h, bound});
    block.bound = std::max(block.bound, bound);
  }
}

int GlobalSearch::CellColumn(double x) const {
  return static_cast<int>(std::lround((x - g_.cells_.x0) / g_.options_.grid_resolution_m));
}

int GlobalSearch::CellRow(double y) const {
  return static_cast<int>(std::lround((y - g_.cells_.y0) / g_.options_.grid_resolution_m));
}

float GlobalSearch::KeepThreshold() const {
  if (kept_scores_.size() < static_cast<size_t>(g_.options_.coarse_keep))
    return -std::numeric_limits<float>::infinity();
  return kept_scores_.front();
}

void GlobalSearch::CoarsePosition(size_t k, const std::vector<uint16_t>& headings) {
  const auto& cells = g_.cells_;
  const int column = CellColumn(g_.positions_[k].x()), row = CellRow(g_.positions_[k].y());
  const auto width = static_cast<unsigned>(cells.width),
             height = static_cast<unsigned>(cells.height);
  const CoarseGain* gain = g_.coarse_gain_.data();
  const size_t n = coarse_count_;
  for (const uint16_t h : headings) {
    const int* off = &offsets_[static_cast<size_t>(h) * n * 2];
    uint32_t sum = 0;
    for (size_t i = 0; i < n; ++i) {
      // Off the grid (a negative cell wraps to a large unsigned one): nothing.
      const auto c = static_cast<unsigned>(column + off[2 * i]);
      const auto r = static_cast<unsigned>(row + off[2 * i + 1]);
      if (c < width && r < height) sum += gain[static_cast<size_t>(r) * width + c];
    }
    scores_[h] = static_cast<float>(sum);  // exact: coarse_points <= 256
    work_ += n;
  }
  AddHits(k, headings, scores_);
}

// The four positions of a level-1 block at once, from the field laid out by
// lattice phase (LatticeGains): the same sums as CoarsePosition's for each,
// and their hits added in the same order.
void GlobalSearch::CoarseBlock(const Block& block) {
  const auto& lattice = g_.lattice_;
  const size_t n = coarse_count_;
  int positions = 0;
  int k[4];
  for (int q = 0; q < 4; ++q) {
    const int column = block.column + q % 2, row = block.row + q / 2;
    k[q] = column < lattice.columns && row < lattice.rows
               ? lattice.position[static_cast<size_t>(row) * lattice.columns + column]
               : -1;
    positions += k[q] >= 0 ? 1 : 0;
  }
  SumFour(0, block.column, block.row, expanding_,
          {&block_scores_[0], &block_scores_[1], &block_scores_[2], &block_scores_[3]});
  work_ += n * expanding_.size() * static_cast<uint64_t>(positions);
  for (int q = 0; q < 4; ++q) {
    if (k[q] >= 0) AddHits(static_cast<size_t>(k[q]), expanding_, block_scores_[q]);
  }
}

void GlobalSearch::AddHits(size_t k, const std::vector<uint16_t>& headings,
                           const std::vector<float>& scores) {
  if (headings.empty()) return;
  // The best heading here, and the best one clearly turned from it (of
  // equal ones the first; the headings come in increasing order).
  int best = headings.front();
  for (const uint16_t h : headings) {
    if (scores[h] > scores[best]) best = h;
  }
  int second = -1;
  for (const uint16_t h : headings) {
    const int apart = std::min(std::abs(h - best), headings_ - std::abs(h - best));
    if (apart >= separation_ && (second < 0 || scores[h] > scores[second])) second = h;
  }
  const size_t keep = static_cast<size_t>(g_.options_.coarse_keep);
  auto add = [&](float score, int heading) {
    hits_.push_back({score, static_cast<int>(k), heading});
    if (kept_scores_.size() < keep) {
      kept_scores_.push_back(score);
      std::push_heap(kept_scores_.begin(), kept_scores_.end(), std::greater<float>());
    } else if (score > kept_scores_.front()) {
      std::pop_heap(kept_scores_.begin(), kept_scores_.end(), std::greater<float>());
      kept_scores_.back() = score;
      std::push_heap(kept_scores_.begin(), kept_scores_.end(), std::greater<float>());
    }
  };
  add(scores[best], best);
  if (second >= 0 && scores[second] >= 0.0f) add(scores[second], second);
}

}  // namespace structloc::localisation_core
