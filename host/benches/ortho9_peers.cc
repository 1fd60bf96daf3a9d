// ortho9 with C++ peers, for scipy_compare.rs: ceres::Solve (its two dense solvers), Ceres' fixed-size
// TinySolver, and a plain fixed-size 9x9 Gauss-Newton as the floor. The same problems, the same start
// (M = I, o = 0), the same analytic Jacobian and the same stopping rule as shared::ortho9: stop once a
// step is at most tol (|x| + tol), tol given on the command line; the other rules are switched off.
//
// stdin: the number of problems, then per problem the number of readings and their x y z (in g).
// argv: tol, repeats.
// stdout: one line per solver, "<name> <median CPU seconds for all problems> <mean iterations> <cost...>".
#include <ceres/ceres.h>
#include <ceres/tiny_solver.h>
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

namespace {

using Readings = std::vector<double>;  // x y z per reading
using Vector9 = Eigen::Matrix<double, 9, 1>;

// The residual |M (m - o)| - 1 of reading m = (x, y, z) and its gradient, M = T K as in shared/src/ortho9.
double Residual(const double* p, const double* m, double* gradient) {
  const double a_yz = p[0], a_zy = p[1], a_zx = p[2], s_x = p[3], s_y = p[4], s_z = p[5];
  const double c0 = m[0] - p[6], c1 = m[1] - p[7], c2 = m[2] - p[8];
  const double a0 = s_x * c0 + a_yz * s_y * c1 + a_zy * s_z * c2;
  const double a1 = s_y * c1 + a_zx * s_z * c2;
  const double a2 = s_z * c2;
  const double length = std::sqrt(a0 * a0 + a1 * a1 + a2 * a2);
  if (gradient == nullptr) return length - 1.0;
  const double u0 = a0 / length, u1 = a1 / length, u2 = a2 / length;
  const double column_y = u0 * a_yz + u1, column_z = u0 * a_zy + u1 * a_zx + u2;
  const double g[9] = {u0 * s_y * c1, u0 * s_z * c2, u1 * s_z * c2,     u0 * c0,         column_y * c1,
                       column_z * c2, -u0 * s_x,     -column_y * s_y,   -column_z * s_z};
  std::copy(g, g + 9, gradient);
  return length - 1.0;
}

// One cost block of all residuals for ceres::Solve.
class Ortho9Cost : public ceres::CostFunction {
 public:
  explicit Ortho9Cost(const Readings* readings) : readings_(readings) {
    set_num_residuals(static_cast<int>(readings->size() / 3));
    mutable_parameter_block_sizes()->push_back(9);
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    double* jacobian = jacobians == nullptr ? nullptr : jacobians[0];
    for (int i = 0; i < num_residuals(); ++i) {
      residuals[i] = Residual(parameters[0], &(*readings_)[3 * i], jacobian == nullptr ? nullptr : jacobian + 9 * i);
    }
    return true;
  }

 private:
  const Readings* readings_;
};

// The same residuals for TinySolver: a dynamic number of residuals, nine parameters, column-major Jacobian.
struct TinyOrtho9 {
  using Scalar = double;
  enum { NUM_RESIDUALS = Eigen::Dynamic, NUM_PARAMETERS = 9 };
  const Readings* readings;

  int NumResiduals() const { return static_cast<int>(readings->size() / 3); }

  bool operator()(const double* p, double* residuals, double* jacobian) const {
    const int n = NumResiduals();
    double gradient[9];
    for (int i = 0; i < n; ++i) {
      residuals[i] = Residual(p, &(*readings)[3 * i], jacobian == nullptr ? nullptr : gradient);
      if (jacobian != nullptr) {
        for (int k = 0; k < 9; ++k) jacobian[k * n + i] = gradient[k];
      }
    }
    return true;
  }
};

struct Result {
  double cost;
  int iterations;
};

Vector9 Start() { return (Vector9() << 0, 0, 0, 1, 1, 1, 0, 0, 0).finished(); }

double Cost(const Readings& readings, const double* p) {
  double cost = 0;
  for (size_t i = 0; i < readings.size(); i += 3) cost += std::pow(Residual(p, &readings[i], nullptr), 2);
  return cost;
}

Result CeresSolve(const Readings& readings, double tol, ceres::LinearSolverType solver) {
  Vector9 p = Start();
  ceres::Problem problem;
  problem.AddResidualBlock(new Ortho9Cost(&readings), nullptr, p.data());
  ceres::Solver::Options options;
  options.linear_solver_type = solver;
  options.parameter_tolerance = tol;
  options.function_tolerance = 0;
  options.gradient_tolerance = 0;
  options.max_num_iterations = 100;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  return {2.0 * summary.final_cost, static_cast<int>(summary.iterations.size()) - 1};
}

Result Tiny(const Readings& readings, double tol) {
  static ceres::TinySolver<TinyOrtho9> solver;  // reused: its storage is sized once
  solver.options.parameter_tolerance = tol;
  solver.options.function_tolerance = 0;
  solver.options.gradient_tolerance = 0;
  solver.options.cost_threshold = 0;
  solver.options.max_num_iterations = 100;
  Vector9 p = Start();
  const auto& summary = solver.Solve(TinyOrtho9{&readings}, &p);
  return {2.0 * summary.final_cost, summary.iterations};
}

// Plain Gauss-Newton: fixed-size normal equations, Cholesky, no damping and no step acceptance test.
Result GaussNewton(const Readings& readings, double tol) {
  Vector9 p = Start();
  for (int iteration = 1; iteration <= 100; ++iteration) {
    Eigen::Matrix<double, 9, 9> jtj = Eigen::Matrix<double, 9, 9>::Zero();
    Vector9 jtr = Vector9::Zero();
    Vector9 gradient;
    for (size_t i = 0; i < readings.size(); i += 3) {
      const double r = Residual(p.data(), &readings[i], gradient.data());
      jtj.selfadjointView<Eigen::Lower>().rankUpdate(gradient);
      jtr += r * gradient;
    }
    const Vector9 step = jtj.selfadjointView<Eigen::Lower>().llt().solve(-jtr);
    if (step.norm() <= tol * (p.norm() + tol)) return {Cost(readings, p.data()), iteration};
    p += step;
  }
  return {NAN, 100};
}

double CpuSeconds() {
  timespec now;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return now.tv_sec + 1e-9 * now.tv_nsec;
}

// Times `fit` over all problems `repeats` times; prints the median CPU time, mean iterations and the costs.
void Run(const char* name, const std::vector<Readings>& problems, int repeats,
         const std::function<Result(const Readings&)>& fit) {
  std::vector<double> seconds;
  std::vector<Result> results;
  for (int repeat = 0; repeat < repeats; ++repeat) {
    results.clear();
    const double began = CpuSeconds();
    for (const auto& readings : problems) results.push_back(fit(readings));
    seconds.push_back(CpuSeconds() - began);
  }
  std::sort(seconds.begin(), seconds.end());
  double iterations = 0;
  for (const auto& r : results) iterations += r.iterations;
  std::printf("%s %.9g %.3f", name, seconds[seconds.size() / 2], iterations / results.size());
  for (const auto& r : results) std::printf(" %.17g", r.cost);
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) return 2;
  const double tol = std::strtod(argv[1], nullptr);
  const int repeats = std::atoi(argv[2]);
  int count = 0;
  std::cin >> count;
  std::vector<Readings> problems(count);
  for (auto& readings : problems) {
    int n = 0;
    std::cin >> n;
    readings.resize(3 * n);
    for (auto& v : readings) std::cin >> v;
  }
  Run("ceres::Solve/DENSE_NORMAL_CHOLESKY", problems, repeats,
      [&](const Readings& r) { return CeresSolve(r, tol, ceres::DENSE_NORMAL_CHOLESKY); });
  Run("ceres::Solve/DENSE_QR", problems, repeats,
      [&](const Readings& r) { return CeresSolve(r, tol, ceres::DENSE_QR); });
  Run("TinySolver", problems, repeats, [&](const Readings& r) { return Tiny(r, tol); });
  Run("Gauss-Newton-floor", problems, repeats, [&](const Readings& r) { return GaussNewton(r, tol); });
  return 0;
}
