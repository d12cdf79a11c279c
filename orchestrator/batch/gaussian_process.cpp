#include "batch/gaussian_process.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <numbers>

namespace orch::batch {

namespace {

Eigen::MatrixXd to_matrix(const std::vector<std::vector<double>>& x) {
  const auto n = static_cast<Eigen::Index>(x.size());
  const auto d = static_cast<Eigen::Index>(x.empty() ? 0 : x.front().size());
  Eigen::MatrixXd m(n, d);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < d; ++j) m(i, j) = x[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
  return m;
}

double kernel(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const std::vector<double>& length) {
  double s = 0;
  for (Eigen::Index j = 0; j < a.size(); ++j) {
    const double t = (a(j) - b(j)) / length[static_cast<std::size_t>(j)];
    s += t * t;
  }
  return std::exp(-0.5 * s);
}

// Correlation matrix of the points (unit signal) plus the nugget on the diagonal.
Eigen::MatrixXd correlation(const Eigen::MatrixXd& x, const GpHyper& h) {
  const Eigen::Index n = x.rows();
  Eigen::MatrixXd k(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    k(i, i) = 1.0 + h.nugget + 1e-9;
    for (Eigen::Index j = 0; j < i; ++j) k(i, j) = k(j, i) = kernel(x.row(i), x.row(j), h.length);
  }
  return k;
}

// The length scales tried: isotropic ones, then each dimension alone shortened and
// lengthened around the best isotropic one (a cheap stand-in for a full ARD search).
const std::vector<double>& length_grid() {
  static const std::vector<double> grid{0.04, 0.06, 0.09, 0.13, 0.2, 0.3, 0.45, 0.7, 1.0, 1.5};
  return grid;
}
const std::vector<double>& nugget_grid() {
  static const std::vector<double> grid{1e-6, 1e-3, 3e-2};
  return grid;
}

}  // namespace

GaussianProcess GaussianProcess::fit_with(const std::vector<std::vector<double>>& points, const std::vector<double>& y,
                                          const GpHyper& hyper) {
  GaussianProcess gp;
  gp.hyper_ = hyper;
  gp.x_ = to_matrix(points);
  const auto n = static_cast<Eigen::Index>(y.size());
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) v(i) = y[static_cast<std::size_t>(i)];
  gp.mean_ = n > 0 ? v.mean() : 0.0;
  v.array() -= gp.mean_;
  gp.llt_.compute(correlation(gp.x_, hyper));
  gp.alpha_ = gp.llt_.solve(v);
  // Profile likelihood: the signal variance that maximises it for this correlation.
  const double quad = std::max(v.dot(gp.alpha_), 1e-12);
  gp.signal_ = quad / static_cast<double>(std::max<Eigen::Index>(n, 1));
  const Eigen::MatrixXd l = gp.llt_.matrixL();
  const double log_det = 2.0 * l.diagonal().array().log().sum();
  gp.log_likelihood_ = -0.5 * static_cast<double>(n) * std::log(gp.signal_) - 0.5 * log_det;
  return gp;
}

GaussianProcess GaussianProcess::fit(const std::vector<std::vector<double>>& x, const std::vector<double>& y) {
  const std::size_t d = x.empty() ? 0 : x.front().size();
  std::optional<GaussianProcess> best;
  const auto consider = [&](const GpHyper& h) {
    GaussianProcess gp = fit_with(x, y, h);
    if (!best || gp.log_likelihood_ > best->log_likelihood_ + 1e-12) best = std::move(gp);
  };
  for (double nugget : nugget_grid())
    for (double len : length_grid()) consider(GpHyper{std::vector<double>(d, len), nugget});
  // Per-dimension refinement: one pass, each dimension's scale from the grid, others kept.
  for (std::size_t j = 0; j < d && d > 1; ++j) {
    const GpHyper start = best->hyper_;
    for (double len : length_grid()) {
      GpHyper h = start;
      h.length[j] = len;
      consider(h);
    }
  }
  return std::move(*best);
}

GpPrediction GaussianProcess::predict(const std::vector<double>& point) const {
  Eigen::VectorXd p(static_cast<Eigen::Index>(point.size()));
  for (Eigen::Index j = 0; j < p.size(); ++j) p(j) = point[static_cast<std::size_t>(j)];
  Eigen::VectorXd k(x_.rows());
  for (Eigen::Index i = 0; i < x_.rows(); ++i) k(i) = kernel(x_.row(i), p, hyper_.length);
  GpPrediction out;
  out.mean = mean_ + k.dot(alpha_);
  const Eigen::VectorXd w = llt_.matrixL().solve(k);
  out.variance = std::max(0.0, signal_ * (1.0 - w.squaredNorm()));
  return out;
}

double normal_pdf(double z) { return std::exp(-0.5 * z * z) / std::sqrt(2.0 * std::numbers::pi); }
double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); }

double expected_improvement(const GpPrediction& p, double best) {
  const double sigma = std::sqrt(p.variance);
  const double gain = best - p.mean;
  if (sigma < 1e-12) return std::max(gain, 0.0);
  const double z = gain / sigma;
  return gain * normal_cdf(z) + sigma * normal_pdf(z);
}

}  // namespace orch::batch
