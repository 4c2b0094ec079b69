// The relative errors the quality presets ask of the hierarchical bake (--quality; docs/accuracy.md
// measures what each delivers), and the default: one place for the bake's, the solver's and the
// gather refinement's defaults, which must agree.
#pragma once

namespace walkrad {

constexpr double kDraftError = 0.4;
constexpr double kMediumError = 0.2;
constexpr double kHighError = 0.1;
constexpr double kFinalError = 0.05;
// Medium since 2026-11-28 (high before): at it the Cornell box is 1.0% off and office-floor's visited
// rooms 2.0% (docs/accuracy.md, "The default is medium").
constexpr double kDefaultError = kMediumError;

}  // namespace walkrad
