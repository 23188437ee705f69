// Unit tests of the derivative helpers of the co-rotational shell tangent (src/elements/so3.*,
// src/elements/shell_frame.*): each named derivative against fourth-order central differences
// of the function it differentiates (test-only finite differences).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <cmath>
#include <vector>

#include "elements/shell_frame.h"
#include "elements/so3.h"

namespace impactfe::test_shell_frame {
namespace {

using Mat3 = Eigen::Matrix3d;
using Vec3 = Eigen::Vector3d;

/// (−g(2h) + 8g(h) − 8g(−h) + g(−2h))/(12h) along each component of x.
template <class F>
Eigen::MatrixXd jacobian_fd(const F& g, const Eigen::VectorXd& x, double h) {
  const int n = static_cast<int>(x.size());
  Eigen::MatrixXd J(g(x).size(), n);
  for (int j = 0; j < n; ++j) {
    auto at = [&](double s) {
      Eigen::VectorXd xp = x;
      xp(j) += s * h;
      return Eigen::VectorXd(g(xp));
    };
    J.col(j) = (8.0 * (at(1) - at(-1)) - (at(2) - at(-2))) / (12.0 * h);
  }
  return J;
}

/// Step for differences in ψ: below t = 1e-4 stay inside the maps' series branch (the closed
/// forms lose eps/t² there, which the quotient would amplify).
double rotation_step(const Vec3& psi) {
  return psi.norm() < 1e-4 ? 1e-5 : 1e-3;
}

double rel_err(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  return (A - B).norm() / std::max(B.norm(), 1e-300);
}

/// Rotation vectors of angle t in every regime of the coefficients: below the 1e-4 series of
/// the maps, inside the derivative series (< 0.3), at its edge, and up to near π.
std::vector<Vec3> rotation_vectors() {
  std::vector<Vec3> out;
  const Vec3 axis = Vec3(0.3, -0.8, 0.5).normalized();
  for (double t : {0.0, 3e-5, 0.01, 0.2, 0.299, 0.301, 1.0, 2.0, 3.0}) out.push_back(t * axis);
  return out;
}

TEST(So3, ExpAndLogAreInverseAndTIsTheLeftJacobian) {
  for (const Vec3& psi : rotation_vectors()) {
    const Mat3 R = so3::exp_map(psi);
    EXPECT_LE((R * R.transpose() - Mat3::Identity()).norm(), 1e-14);
    EXPECT_LE((so3::log_map(R) - psi).norm(), 1e-12) << psi.norm();
    // δR Rᵀ = spin(T δψ): spin⁻¹ of ∂R/∂ψ_j Rᵀ is column j of T.
    Mat3 T_fd;
    for (int j = 0; j < 3; ++j) {
      const auto Rj = [&](const Eigen::VectorXd& x) {
        Vec3 p = psi;
        p(j) = x(0);
        const Mat3 Rp = so3::exp_map(p);
        return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(Rp.data(), 9));
      };
      const Eigen::VectorXd dR = jacobian_fd(Rj, Eigen::VectorXd::Constant(1, psi(j)), 1e-3);
      const Mat3 W = Eigen::Map<const Mat3>(dR.data()) * R.transpose();
      T_fd.col(j) = Vec3(W(2, 1), W(0, 2), W(1, 0));
    }
    EXPECT_LE(rel_err(so3::left_jacobian(psi), T_fd), 1e-10) << psi.norm();
    EXPECT_LE((so3::left_jacobian(psi) * so3::left_jacobian_inverse(psi) - Mat3::Identity()).norm(),
              1e-13)
        << psi.norm();
    // log and T(θ)⁻¹ from one quaternion: the two calls to round-off.
    Mat3 Ji;
    const Vec3 theta = so3::log_quaternion_and_left_jacobian_inverse(Eigen::Quaterniond(R), Ji);
    EXPECT_LE((theta - so3::log_map(R)).norm(), 1e-15 * std::max(1.0, psi.norm()));
    EXPECT_LE(rel_err(Ji, so3::left_jacobian_inverse(so3::log_map(R))), 1e-12) << psi.norm();
    // exp as a quaternion and T together: the two maps to round-off; log from the quaternion
    // and from its matrix the same.
    Eigen::Quaterniond q;
    Mat3 T_both;
    so3::exp_quaternion_and_left_jacobian(psi, q, T_both);
    EXPECT_LE(std::abs(q.norm() - 1.0), 1e-15) << psi.norm();
    EXPECT_LE((q.toRotationMatrix() - R).norm(), 1e-15 * 3.0) << psi.norm();
    EXPECT_LE(rel_err(T_both, so3::left_jacobian(psi)), 1e-12) << psi.norm();
    Mat3 Ji_q;
    EXPECT_LE((so3::log_quaternion_and_left_jacobian_inverse(q, Ji_q) - theta).norm(),
              1e-14 * std::max(1.0, psi.norm()))
        << psi.norm();
    EXPECT_LE(rel_err(Ji_q, Ji), 1e-12) << psi.norm();
    // q and −q are one rotation.
    Eigen::Quaterniond minus_q = q;
    minus_q.coeffs() *= -1.0;
    EXPECT_EQ(so3::log_quaternion_and_left_jacobian_inverse(minus_q, Ji_q),
              so3::log_quaternion_and_left_jacobian_inverse(q, Ji_q))
        << psi.norm();
  }
}

TEST(So3, DerivativeOfLeftJacobianTransposeTimesVector) {
  const Vec3 v(0.7, -1.3, 0.4);
  for (const Vec3& psi : rotation_vectors()) {
    const auto g = [&](const Eigen::VectorXd& p) {
      return Eigen::VectorXd(so3::left_jacobian(Vec3(p)).transpose() * v);
    };
    const Mat3 fd = jacobian_fd(g, psi, rotation_step(psi));
    EXPECT_LE(rel_err(so3::d_left_jacobian_transpose(psi, v), fd), 1e-10) << psi.norm();
  }
}

TEST(So3, DerivativeOfLeftJacobianInverseTransposeTimesVector) {
  const Vec3 m(-0.2, 0.9, 1.1);
  for (const Vec3& theta : rotation_vectors()) {
    const auto g = [&](const Eigen::VectorXd& p) {
      return Eigen::VectorXd(so3::left_jacobian_inverse(Vec3(p)).transpose() * m);
    };
    const Mat3 fd = jacobian_fd(g, theta, rotation_step(theta));
    // Near π, T⁻¹ grows like 1/(π − t): a looser bound for the difference quotient there.
    const double tol = theta.norm() > 2.5 ? 1e-8 : 1e-10;
    EXPECT_LE(rel_err(so3::d_left_jacobian_inverse_transpose(theta, m), fd), tol) << theta.norm();
  }
}

/// Corner sets: a warped quad in general position and a triangle.
std::vector<ShellCorners> corner_sets() {
  const Mat3 R = Eigen::AngleAxisd(0.9, Vec3(1, 2, -1).normalized()).toRotationMatrix();
  ShellCorners quad(3, 4), tri(3, 3);
  quad << 0.1, 2.2, 1.9, -0.2, -0.05, 0.1, 1.3, 1.0, 0.0, 0.05, 0.2, -0.1;
  tri << 0.1, 2.2, 0.7, -0.05, 0.3, 1.4, 0.0, 0.1, -0.2;
  quad = R * quad;
  tri = R * tri;
  return {quad, tri};
}

Eigen::VectorXd flat(const ShellCorners& x) {
  return Eigen::Map<const Eigen::VectorXd>(x.data(), x.size());
}
ShellCorners corners(const Eigen::VectorXd& v) {
  return Eigen::Map<const ShellCorners>(v.data(), 3, v.size() / 3);
}

TEST(ShellFrame, SpinMatrixGivesTheFrameVariation) {
  // δe_i = (G δx) × e_i for every column of the frame.
  for (const ShellCorners& x : corner_sets()) {
    const ShellFrame f = shell_frame(x, true);
    EXPECT_LE((f.R.transpose() * f.R - Mat3::Identity()).norm(), 1e-14);
    const auto R_of = [](const Eigen::VectorXd& v) {
      const Mat3 R = shell_frame(corners(v), false).R;
      return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(R.data(), 9));
    };
    const Eigen::MatrixXd dR = jacobian_fd(R_of, flat(x), 1e-3);
    for (int j = 0; j < dR.cols(); ++j) {
      const Mat3 W = Eigen::Map<const Mat3>(dR.col(j).data()) * f.R.transpose();
      EXPECT_LE((Vec3(W(2, 1), W(0, 2), W(1, 0)) - Vec3(f.G.col(j))).norm(), 1e-10) << j;
    }
  }
}

TEST(ShellFrame, NormalAndSideHessians) {
  const Vec3 y(0.4, -1.1, 0.8);
  for (const ShellCorners& x : corner_sets()) {
    const ShellFrame f = shell_frame(x, true);
    const auto grad_e3 = [&](const Eigen::VectorXd& v) {
      return Eigen::VectorXd(shell_frame(corners(v), true).De3.transpose() * y);
    };
    const auto grad_e1 = [&](const Eigen::VectorXd& v) {
      return Eigen::VectorXd(shell_frame(corners(v), true).De1.transpose() * y);
    };
    const ShellMatNN H3 = normal_hessian(f, y), H1 = side_hessian(f, y);
    EXPECT_LE(rel_err(H3, jacobian_fd(grad_e3, flat(x), 1e-3)), 1e-10);
    EXPECT_LE(rel_err(H1, jacobian_fd(grad_e1, flat(x), 1e-3)), 1e-10);
    EXPECT_LE((H3 - H3.transpose()).norm(), 1e-12 * H3.norm());
    EXPECT_LE((H1 - H1.transpose()).norm(), 1e-12 * H1.norm());
  }
}

TEST(ShellFrame, DerivativeOfSpinMatrixTransposeTimesVector) {
  const Vec3 w(-0.6, 0.3, 1.7);
  for (const ShellCorners& x : corner_sets()) {
    const ShellFrame f = shell_frame(x, true);
    const auto Gt_w = [&](const Eigen::VectorXd& v) {
      return Eigen::VectorXd(shell_frame(corners(v), true).G.transpose() * w);
    };
    EXPECT_LE(rel_err(frame_spin_derivative(f, w), jacobian_fd(Gt_w, flat(x), 1e-3)), 1e-10);
  }
}

}  // namespace
}  // namespace impactfe::test_shell_frame
