#include "luxel/lighting/core/cost_model.hpp"

#include <algorithm>
#include <cmath>

namespace luxel::lighting {

std::string_view name(WorkKind kind) {
    switch (kind) {
        case WorkKind::PhotonProbe:
            return "photon_probe";
        case WorkKind::GroupRetrace:
            return "group_retrace";
        case WorkKind::CausticSlice:
            return "caustic_slice";
        case WorkKind::AimRebuild:
            return "aim_rebuild";
        case WorkKind::IimGather:
            return "iim_gather";
        case WorkKind::ProbeGather:
            return "probe_gather";
    }
    return "unknown";
}

namespace {

/// A finite, non-negative value or `fallback`: settings come from configuration files.
double sane(double value, double fallback) {
    return std::isfinite(value) && value >= 0.0 ? value : fallback;
}

}  // namespace

CostModel::CostModel(CostModelSettings settings) : settings_(settings) {
    const CostModelSettings defaults;
    for (std::size_t k = 0; k < kWorkKindCount; ++k) {
        settings_.prior_ms[k] = sane(settings_.prior_ms[k], defaults.prior_ms[k]);
    }
    settings_.prior_weight = sane(settings_.prior_weight, defaults.prior_weight);
    // smoothing must be in (0, 1]: 0 would never learn, above 1 would oscillate.
    if (!(settings_.smoothing > 0.0 && settings_.smoothing <= 1.0)) {
        settings_.smoothing = defaults.smoothing;
    }
    settings_.prior_relative_deviation =
        sane(settings_.prior_relative_deviation, defaults.prior_relative_deviation);
    settings_.error_factor = sane(settings_.error_factor, defaults.error_factor);
    settings_.min_relative_error = sane(settings_.min_relative_error, defaults.min_relative_error);
    settings_.min_error_ms = sane(settings_.min_error_ms, defaults.min_error_ms);
    reset();
}

void CostModel::reset() {
    for (std::size_t k = 0; k < kWorkKindCount; ++k) {
        costs_[k].mean_ms = settings_.prior_ms[k];
        costs_[k].deviation_ms = settings_.prior_ms[k] * settings_.prior_relative_deviation;
        costs_[k].samples = 0;
    }
}

void CostModel::record(WorkKind kind, double size, double measured_ms) {
    if (!std::isfinite(size) || !std::isfinite(measured_ms) || size <= 0.0 || measured_ms < 0.0) {
        return;
    }
    const double per_unit = measured_ms / size;
    if (!std::isfinite(per_unit)) {
        return;  // a denormal size can overflow the division
    }
    KindCost& c = costs_[index(kind)];
    // While the history is short, a running mean in which the prior counts as prior_weight
    // measurements; then exponential smoothing, whose weight never falls below `smoothing`.
    const double n = static_cast<double>(c.samples);
    const double weight = std::max(settings_.smoothing, 1.0 / (settings_.prior_weight + n + 1.0));
    // The deviation is of the prediction the scheduler used (the mean before this sample): that
    // is the error the frame budget suffers.
    const double error = std::abs(per_unit - c.mean_ms);
    c.mean_ms += weight * (per_unit - c.mean_ms);
    if (c.samples == 0) {
        // The first error measures how wrong the prior was, not how noisy the kind is: start
        // the deviation from the same relative guess, around the measured mean.
        c.deviation_ms = settings_.prior_relative_deviation * c.mean_ms;
    } else {
        c.deviation_ms += weight * (error - c.deviation_ms);
    }
    c.samples += 1;
}

double CostModel::predict(WorkKind kind, double size) const {
    if (!std::isfinite(size) || size <= 0.0) {
        return 0.0;
    }
    return costs_[index(kind)].mean_ms * size;
}

double CostModel::prediction_error(WorkKind kind, double size) const {
    if (!std::isfinite(size) || size <= 0.0) {
        return settings_.min_error_ms;
    }
    const KindCost& c = costs_[index(kind)];
    const double per_unit =
        std::max(settings_.error_factor * c.deviation_ms, settings_.min_relative_error * c.mean_ms);
    return per_unit * size + settings_.min_error_ms;
}

}  // namespace luxel::lighting
