#pragma once

// Gauss-Legendre quadrature for the closed forms the reference tests integrate themselves
// (independently of the integrator under test).

#include <cmath>
#include <cstddef>
#include <vector>

#include <glm/gtc/constants.hpp>

namespace luxel::testing {

/// The n-point Gauss-Legendre rule on [-1, 1]: exact for polynomials of degree 2n - 1.
struct GaussLegendre {
    std::vector<double> nodes;
    std::vector<double> weights;
};

/// Nodes are the roots of the Legendre polynomial P_n, found by Newton's method from the
/// asymptotic guess cos(pi (i + 3/4) / (n + 1/2)); weights 2 / ((1 - x^2) P_n'(x)^2).
inline GaussLegendre gauss_legendre(int n) {
    GaussLegendre rule;
    for (int i = 0; i < n; ++i) {
        double x = std::cos(glm::pi<double>() * (static_cast<double>(i) + 0.75) /
                            (static_cast<double>(n) + 0.5));
        double derivative = 1.0;
        for (int iteration = 0; iteration < 100; ++iteration) {
            // The three-term recurrence k P_k = (2k - 1) x P_{k-1} - (k - 1) P_{k-2}.
            double previous = 1.0;
            double current = x;
            for (int k = 2; k <= n; ++k) {
                const double next = (static_cast<double>(2 * k - 1) * x * current -
                                     static_cast<double>(k - 1) * previous) /
                                    static_cast<double>(k);
                previous = current;
                current = next;
            }
            derivative = static_cast<double>(n) * (x * current - previous) / (x * x - 1.0);
            const double step = current / derivative;
            x -= step;
            if (std::abs(step) < 1e-15) {
                break;
            }
        }
        rule.nodes.push_back(x);
        rule.weights.push_back(2.0 / ((1.0 - x * x) * derivative * derivative));
    }
    return rule;
}

/// The integral of f over [a, b] by `panels` equal panels of the rule.
template <typename F>
double integrate(const GaussLegendre& rule, double a, double b, int panels, F&& f) {
    const double width = (b - a) / static_cast<double>(panels);
    double sum = 0.0;
    for (int p = 0; p < panels; ++p) {
        const double mid = a + (static_cast<double>(p) + 0.5) * width;
        for (std::size_t i = 0; i < rule.nodes.size(); ++i) {
            sum += rule.weights[i] * f(mid + 0.5 * width * rule.nodes[i]);
        }
    }
    return 0.5 * width * sum;
}

/// The integral of f(s, t) over [a0, b0] x [a1, b1] by panels0 x panels1 panels of the rule.
template <typename F>
double integrate_2d(const GaussLegendre& rule, double a0, double b0, int panels0, double a1,
                    double b1, int panels1, F&& f) {
    return integrate(rule, a0, b0, panels0, [&](double s) {
        return integrate(rule, a1, b1, panels1, [&](double t) { return f(s, t); });
    });
}

}  // namespace luxel::testing
