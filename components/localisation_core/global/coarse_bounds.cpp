// The coarse score's block bounds (see header): each level's grid is the
// coarse gain dilated by a square anchored at its corner (OpenCV's dilate
// takes the largest value under the square).
#include "structloc/localisation_core/global/coarse_bounds.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace structloc::localisation_core {

CoarseGain ToCoarseGain(double gain) {
  return static_cast<CoarseGain>(std::lround(65535.0 * std::clamp(gain, 0.0, 1.0)));
}

CoarseBounds::CoarseBounds(const std::vector<CoarseGain>& gain, int width, int height,
                           int step_cells, int levels)
    : width_(width), height_(height) {
  const cv::Mat source(height, width, CV_16U, const_cast<CoarseGain*>(gain.data()));
  for (int level = 1; level <= levels; ++level) {
    // A point o cells from the block's positions p .. p + reach falls into
    // cells p + o .. p + o + reach. The grid has `reach` more columns and
    // rows before the field's first, for points that fall before it from
    // the block's first position but not from its last.
    const int reach = ((1 << level) - 1) * step_cells;
    cv::Mat padded(height + reach, width + reach, CV_16U, cv::Scalar(0));
    source.copyTo(padded(cv::Rect(reach, reach, width, height)));
    const cv::Mat square = cv::Mat::ones(reach + 1, reach + 1, CV_8U);
    cv::Mat dilated;
    cv::dilate(padded, dilated, square, cv::Point(0, 0), 1, cv::BORDER_CONSTANT, cv::Scalar(0));
    grids_.emplace_back(dilated.begin<CoarseGain>(), dilated.end<CoarseGain>());
    reach_.push_back(reach);
  }
}

}  // namespace structloc::localisation_core
