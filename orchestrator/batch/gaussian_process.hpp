#pragma once
// A small Gaussian-process regression for the search (search_proposal.hpp): points in the unit
// cube, a squared-exponential kernel with one length scale per dimension, a constant mean.
// Hyperparameters by maximum (profile) marginal likelihood over a fixed grid, so a fit is a
// pure function of its data: the search stays deterministic for a seed. Sizes are tiny (a
// search has tens to a few hundred runs), so a dense Cholesky factorisation is enough.
#include <Eigen/Dense>
#include <vector>

namespace orch::batch {

struct GpPrediction {
  double mean = 0;
  double variance = 0;  // of the latent function (without the nugget)
};

struct GpHyper {
  std::vector<double> length;  // per dimension, in unit-cube coordinates
  double nugget = 1e-6;        // noise variance relative to the signal's
};

class GaussianProcess {
 public:
  // Fits to `x` (n points of d coordinates in [0, 1]) and `y`, choosing the hyperparameters
  // by marginal likelihood. n >= 1.
  static GaussianProcess fit(const std::vector<std::vector<double>>& x, const std::vector<double>& y);
  // Fits with given hyperparameters (the batch's "believer" points keep the first fit's).
  static GaussianProcess fit_with(const std::vector<std::vector<double>>& x, const std::vector<double>& y,
                                  const GpHyper& hyper);

  [[nodiscard]] GpPrediction predict(const std::vector<double>& point) const;
  [[nodiscard]] const GpHyper& hyper() const { return hyper_; }
  [[nodiscard]] double log_likelihood() const { return log_likelihood_; }

 private:
  Eigen::MatrixXd x_;
  Eigen::VectorXd alpha_;
  Eigen::LLT<Eigen::MatrixXd> llt_;
  GpHyper hyper_;
  double mean_ = 0;
  double signal_ = 1;  // signal variance, in y's units squared
  double log_likelihood_ = 0;
};

// Standard normal density and distribution function.
double normal_pdf(double z);
double normal_cdf(double z);
// Expected improvement below `best` of a prediction (minimisation).
double expected_improvement(const GpPrediction& p, double best);

}  // namespace orch::batch
