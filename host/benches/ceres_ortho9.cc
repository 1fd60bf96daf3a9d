// ortho9 with Ceres, for scipy_compare.rs: the same problems, the same start (M = I, o = 0) and
// analytic Jacobian, one cost block of all residuals, its fastest dense linear solvers.
//
// stdin: the number of problems, then per problem the number of readings and their x y z (in g).
// stdout: one line per solver, "<name> <best-of-repeats seconds for all problems> <cost...>".
#include <ceres/ceres.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <vector>

namespace {

using Readings = std::vector<double>;  // x y z per reading

// Residuals |M (m_i - o)| - 1 of all readings, M = T K as in shared/src/ortho9.
class Ortho9Cost : public ceres::CostFunction {
 public:
  explicit Ortho9Cost(const Readings* readings) : readings_(readings) {
    set_num_residuals(static_cast<int>(readings->size() / 3));
    mutable_parameter_block_sizes()->push_back(9);
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double* p = parameters[0];
    const double a_yz = p[0], a_zy = p[1], a_zx = p[2], s_x = p[3], s_y = p[4], s_z = p[5];
    const int n = num_residuals();
    for (int i = 0; i < n; ++i) {
      const double c0 = (*readings_)[3 * i] - p[6];
      const double c1 = (*readings_)[3 * i + 1] - p[7];
      const double c2 = (*readings_)[3 * i + 2] - p[8];
      const double a0 = s_x * c0 + a_yz * s_y * c1 + a_zy * s_z * c2;
      const double a1 = s_y * c1 + a_zx * s_z * c2;
      const double a2 = s_z * c2;
      const double length = std::sqrt(a0 * a0 + a1 * a1 + a2 * a2);
      residuals[i] = length - 1.0;
      if (jacobians == nullptr || jacobians[0] == nullptr) continue;
      const double u0 = a0 / length, u1 = a1 / length, u2 = a2 / length;
      const double column_y = u0 * a_yz + u1, column_z = u0 * a_zy + u1 * a_zx + u2;
      double* row = jacobians[0] + 9 * i;
      row[0] = u0 * s_y * c1;
      row[1] = u0 * s_z * c2;
      row[2] = u1 * s_z * c2;
      row[3] = u0 * c0;
      row[4] = column_y * c1;
      row[5] = column_z * c2;
      row[6] = -u0 * s_x;
      row[7] = -column_y * s_y;
      row[8] = -column_z * s_z;
    }
    return true;
  }

 private:
  const Readings* readings_;
};

double Fit(const Readings& readings, ceres::LinearSolverType solver) {
  double p[9] = {0, 0, 0, 1, 1, 1, 0, 0, 0};
  ceres::Problem problem;
  problem.AddResidualBlock(new Ortho9Cost(&readings), nullptr, p);
  ceres::Solver::Options options;
  options.linear_solver_type = solver;
  options.function_tolerance = 1e-12;
  options.parameter_tolerance = 1e-12;
  options.gradient_tolerance = 1e-12;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  return 2.0 * summary.final_cost;  // Ceres' cost is half the sum of squares
}

}  // namespace

int main() {
  int count = 0;
  std::cin >> count;
  std::vector<Readings> problems(count);
  for (auto& readings : problems) {
    int n = 0;
    std::cin >> n;
    readings.resize(3 * n);
    for (auto& v : readings) std::cin >> v;
  }
  const std::pair<const char*, ceres::LinearSolverType> solvers[] = {
      {"DENSE_NORMAL_CHOLESKY", ceres::DENSE_NORMAL_CHOLESKY}, {"DENSE_QR", ceres::DENSE_QR}};
  for (const auto& [name, solver] : solvers) {
    double best = 1e300;
    std::vector<double> costs;
    for (int repeat = 0; repeat < 5; ++repeat) {
      costs.clear();
      const auto began = std::chrono::steady_clock::now();
      for (const auto& readings : problems) costs.push_back(Fit(readings, solver));
      best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count());
    }
    std::printf("%s %.9g", name, best);
    for (double c : costs) std::printf(" %.17g", c);
    std::printf("\n");
  }
  return 0;
}
