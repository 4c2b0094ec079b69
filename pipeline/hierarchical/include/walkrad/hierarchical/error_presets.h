// The relative errors the quality presets ask of the hierarchical bake (--quality), and the default:
// one place for the bake's, the solver's and the gather refinement's defaults, which must agree.
#pragma once

namespace walkrad {

constexpr double kDraftError = 0.4;
constexpr double kMediumError = 0.2;
constexpr double kHighError = 0.1;
constexpr double kFinalError = 0.05;
// The default is medium: it holds the Cornell box to about 1% weighted RMS against its reference and
// office-floor's visited rooms to about 2%, a twentieth and a tenth of the error it asks for, at about
// half the time of high.
constexpr double kDefaultError = kMediumError;

}  // namespace walkrad
