// The IES LM-63 reader: every version line and the headerless file, the multipliers, TILT=INCLUDE,
// the type C symmetries against formulas with the same symmetry, exact bilinear interpolation, the
// light frame of types C, B and A, flux against closed forms, and malformed or truncated files
// refused with the line.
#include "walkrad/formats/ies.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>

#include <gtest/gtest.h>

#include "walkrad/formats/error.h"

namespace walkrad {
namespace {

namespace fs = std::filesystem;
constexpr double kDeg = kPi / 180;

// A profile to write: angles and a formula for the candela in the file's own angles.
struct Spec {
  std::string head = "IESNA:LM-63-2002\n[TEST] walkrad\n[MANUFAC] none\n";
  std::string tilt = "TILT=NONE\n";
  int type = 1;
  double multiplier = 1, ballast = 1, ballast_lamp = 1;
  std::vector<double> vertical, horizontal;
  std::function<double(double v, double h)> cd;
  std::string eol = "\n";
};

std::vector<double> steps(double from, double to, double step) {
  std::vector<double> a;
  for (int i = 0; from + i * step <= to + 1e-9; ++i) a.push_back(from + i * step);
  return a;
}

// Numbers 7 to a line, so that lists wrap the way published files do.
std::string text(const Spec& s) {
  std::string out = s.head + s.tilt, line;
  int on_line = 0;
  auto put = [&](double x) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    line += (on_line ? " " : "") + std::string(buf);
    if (++on_line == 7) out += line + s.eol, line.clear(), on_line = 0;
  };
  auto end_line = [&] {
    if (on_line) out += line + s.eol, line.clear(), on_line = 0;
  };
  for (double x : {1.0, -1.0, s.multiplier, double(s.vertical.size()), double(s.horizontal.size()), double(s.type),
                   2.0, 0.5, 0.4, 0.1})
    put(x);
  end_line();
  for (double x : {s.ballast, s.ballast_lamp, 35.0}) put(x);
  end_line();
  for (double v : s.vertical) put(v);
  end_line();
  for (double h : s.horizontal) put(h);
  end_line();
  for (double h : s.horizontal) {
    for (double v : s.vertical) put(s.cd(v, h));
    end_line();
  }
  return out;
}

IesProfile parse(const Spec& s) { return parse_ies(text(s), "test.ies"); }

// Type C's direction (ies.h): vertical γ from −Z, horizontal C from +X towards +Y.
Vec3 dir_c(double g, double c) {
  return {std::sin(g * kDeg) * std::cos(c * kDeg), std::sin(g * kDeg) * std::sin(c * kDeg), -std::cos(g * kDeg)};
}
Vec3 dir_b(double v, double h) {
  return std::cos(h * kDeg) * (std::cos(v * kDeg) * Vec3(0, 0, -1) + std::sin(v * kDeg) * Vec3(1, 0, 0)) +
         std::sin(h * kDeg) * Vec3(0, -1, 0);
}
Vec3 dir_a(double v, double h) {
  return std::cos(v * kDeg) * (std::cos(h * kDeg) * Vec3(0, 0, -1) + std::sin(h * kDeg) * Vec3(0, -1, 0)) +
         std::sin(v * kDeg) * Vec3(1, 0, 0);
}

// The refusal of `text`: its code, place and message.
InputError refusal(const std::string& t) {
  try {
    parse_ies(t, "bad.ies");
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "accepted:\n" << t;
  return InputError("", "", "");
}

// --- Versions, fields, multipliers, tilt -------------------------------------------------------

Spec small() {
  Spec s;
  s.vertical = {0, 45, 90};
  s.horizontal = {0, 90};
  s.cd = [](double v, double h) { return 100 - v + h / 10; };
  return s;
}

TEST(IesParse, EveryVersionLineAndTheHeaderlessFile) {
  const std::pair<std::string, std::string> cases[] = {
      {"IESNA:LM-63-1995\n[TEST] a\n", "LM-63-1995"},
      {"IESNA:LM-63-2002\n[TEST] a\n[ISSUEDATE] 2002\n", "LM-63-2002"},
      {"IES:LM-63-2019\n[TEST] a\n[ISSUEDATE] 2019\n[_CUSTOM] anything: =,; \"\n", "LM-63-2019"},
      {"IESNA91\n[TEST] a\n", "LM-63-1991"},
      {"ACME luminaire 12\nfree label text, 3 4 5\n", "LM-63-1986"},
      {"", "LM-63-1986"}};  // TILT= on the first line
  for (const auto& [head, version] : cases) {
    Spec s = small();
    s.head = head;
    const IesProfile p = parse(s);
    EXPECT_EQ(p.version, version) << head;
    EXPECT_EQ(p.source, "test.ies");
    EXPECT_EQ(p.photometry, IesProfile::Photometry::C);
    EXPECT_EQ(p.vertical, (std::vector<double>{0, 45, 90}));
    EXPECT_EQ(p.horizontal, (std::vector<double>{0, 90}));
    EXPECT_EQ(p.candela, (std::vector<double>{100, 55, 10, 109, 64, 19}));
    EXPECT_EQ(p.lamps, 1);
    EXPECT_EQ(p.lumens_per_lamp, -1);
    EXPECT_EQ(p.input_watts, 35);
    EXPECT_TRUE(p.tilt_angles.empty());
    EXPECT_EQ(p.tilt_factor(30), 1);
    EXPECT_EQ(p.max_candela(), 109);
  }
}

TEST(IesParse, CrLfLfCommasAndWrappingReadTheSame) {
  Spec s = small();
  const IesProfile lf = parse(s);
  s.eol = "\r\n";
  s.head = "IESNA:LM-63-2002\r\n[TEST] walkrad\r\n";
  s.tilt = "TILT=NONE\r\n";
  EXPECT_EQ(parse(s).candela, lf.candela);
  const std::string one_per_line =
      "IESNA:LM-63-1995\nTILT=NONE\n1\n-1\n1\n3\n2\n1\n2\n0.5\n0.4\n0.1\n1\n1\n35\n0\n45\n90\n0\n90\n"
      "100\n55\n10\n109\n64\n19\n";
  EXPECT_EQ(parse_ies(one_per_line, "x").candela, lf.candela);
  const std::string commas = "IESNA:LM-63-1995\nTILT=NONE\n1,-1,1,3,2,1,2,0.5,0.4,0.1\n1, 1, 35\n0,45,90\n0 ,90\n"
                             "100,55,10,\n109,64,19\n";
  EXPECT_EQ(parse_ies(commas, "x").candela, lf.candela);
  const std::string forms = "IESNA:LM-63-1995\nTILT=NONE\n1.0 -1 +1 3e0 2 1 2 .5 0.4 1e-1\n1. 1 35\n0 45 90.\n"
                            "0 90\n100 55 10 109 64 19\n  \n\n";  // trailing blank lines are fine
  EXPECT_EQ(parse_ies(forms, "x").candela, lf.candela);
}

TEST(IesParse, MultiplierAndBallastFactorsApplied) {
  Spec s = small();
  s.cd = [](double, double) { return 100.0; };
  s.multiplier = 2;
  s.ballast = 0.5;
  s.ballast_lamp = 0.8;
  s.head = "IESNA:LM-63-1995\n";  // the ballast-lamp photometric factor multiplies
  for (double c : parse(s).candela) EXPECT_DOUBLE_EQ(c, 80);
  s.head = "IESNA91\n";
  for (double c : parse(s).candela) EXPECT_DOUBLE_EQ(c, 80);
  s.head = "IESNA:LM-63-2002\n";  // the same field is "future use" since 2002: ignored
  for (double c : parse(s).candela) EXPECT_DOUBLE_EQ(c, 100);
  s.head = "IES:LM-63-2019\n";
  EXPECT_DOUBLE_EQ(parse(s).max_candela(), 100);
}

TEST(IesParse, TiltIncludeParsedAndInterpolated) {
  Spec s = small();
  s.tilt = "TILT=INCLUDE\n1\n7\n0 15 30\n45 60 75 90\n1.0 .95 .9\n.85 .8 .75 .7\n";
  const IesProfile p = parse(s);
  EXPECT_EQ(p.lamp_geometry, 1);
  EXPECT_EQ(p.tilt_angles, (std::vector<double>{0, 15, 30, 45, 60, 75, 90}));
  EXPECT_EQ(p.tilt_factors, (std::vector<double>{1, .95, .9, .85, .8, .75, .7}));
  EXPECT_DOUBLE_EQ(p.tilt_factor(0), 1);
  EXPECT_DOUBLE_EQ(p.tilt_factor(7.5), 0.975);
  EXPECT_DOUBLE_EQ(p.tilt_factor(50), 0.85 - 0.05 / 3);
  EXPECT_DOUBLE_EQ(p.tilt_factor(90), 0.7);
  EXPECT_DOUBLE_EQ(p.tilt_factor(-10), 1);   // clamped at the ends
  EXPECT_DOUBLE_EQ(p.tilt_factor(120), 0.7);
  EXPECT_EQ(p.candela, parse(small()).candela);
}

TEST(IesParse, TiltFileIsAMissingFeature) {
  Spec s = small();
  s.tilt = "TILT=lamp.tlt\n";
  const InputError e = refusal(text(s));
  EXPECT_EQ(e.code(), kExitMissingFeature);
  EXPECT_EQ(e.place(), "line 4");
  EXPECT_NE(e.message().find("TILT=INCLUDE"), std::string::npos) << e.what();
}

// --- Symmetry and interpolation -----------------------------------------------------------------

double radial(double g) { return 60 + 40 * std::cos(g * kDeg); }

// Builds a type C profile on 2.5° steps over γ 0..180 and `horizontal` from
// f(γ, C) = radial(γ) + 20 sin γ · azimuthal(C) (one value at each pole, as a luminaire has), then
// checks intensity() against f in every direction (within the interpolation error, h²/8 · |f''| ≲
// 0.03 here) and that the mirror images the symmetry names give the same candela.
void check_symmetry(const std::string& head, std::vector<double> horizontal, double (*azimuthal)(double c),
                    bool mirror_y, bool mirror_x) {
  const auto f = [azimuthal](double g, double c) { return radial(g) + 20 * std::sin(g * kDeg) * azimuthal(c); };
  Spec s;
  s.head = head;
  s.vertical = steps(0, 180, 2.5);
  s.horizontal = std::move(horizontal);
  s.cd = f;
  const IesProfile p = parse(s);
  for (double g = 0; g <= 180; g += 7.3) {
    for (double c = 0; c < 360; c += 4.1) {
      const Vec3 d = dir_c(g, c);
      const double i = p.intensity(d);
      EXPECT_NEAR(i, f(g, c), 0.1) << "gamma " << g << " C " << c;
      if (mirror_y) EXPECT_NEAR(p.intensity({d.x, -d.y, d.z}), i, 1e-9 * i) << g << " " << c;
      if (mirror_x) EXPECT_NEAR(p.intensity({-d.x, d.y, d.z}), i, 1e-9 * i) << g << " " << c;
      if (mirror_x && mirror_y) EXPECT_NEAR(p.intensity({-d.x, -d.y, d.z}), i, 1e-9 * i) << g << " " << c;
    }
  }
}

TEST(IesSymmetry, RotationalSingleHorizontalAngle) {
  check_symmetry("IESNA:LM-63-2002\n", {0}, [](double) { return 0.0; }, true, true);
}

TEST(IesSymmetry, QuadrantZeroToNinety) {
  // cos 2C: even about the 0–180 plane and about the 90–270 plane.
  check_symmetry("IESNA:LM-63-2002\n", steps(0, 90, 2.5),
                 [](double c) { return std::cos(2 * c * kDeg); }, true, true);
}

TEST(IesSymmetry, BilateralZeroToOneEighty) {
  // cos C: even about the 0–180 plane only (a quadrant mirror would be caught).
  check_symmetry("IESNA:LM-63-2002\n", steps(0, 180, 2.5),
                 [](double c) { return std::cos(c * kDeg); }, true, false);
}

TEST(IesSymmetry, FullZeroToThreeSixty) {
  check_symmetry("IES:LM-63-2019\n", steps(0, 360, 2.5),
                 [](double c) { return 0.6 * std::cos(c * kDeg) + 0.8 * std::sin(c * kDeg); },
                 false, false);
}

TEST(IesSymmetry, Lm63_1995NinetyToTwoSeventy) {
  // sin C: even about the 90–270 plane (C → 180 − C) only.
  check_symmetry("IESNA:LM-63-1995\n", steps(90, 270, 2.5),
                 [](double c) { return std::sin(c * kDeg); }, false, true);
}

TEST(IesSymmetry, NothingOutsideTheVerticalRange) {
  Spec s = small();  // 0..90: a downlight
  IesProfile p = parse(s);
  EXPECT_GT(p.intensity(dir_c(89.9, 30)), 0);
  EXPECT_EQ(p.intensity(dir_c(90.1, 30)), 0);
  EXPECT_EQ(p.intensity({0, 0, 1}), 0);
  s.vertical = {90, 135, 180};  // an uplight
  s.cd = [](double v, double) { return 300 - v; };
  p = parse(s);
  EXPECT_EQ(p.intensity({0, 0, -1}), 0);
  EXPECT_EQ(p.intensity(dir_c(89.9, 0)), 0);
  EXPECT_DOUBLE_EQ(p.intensity({1, 0, 0}), 210);
  EXPECT_DOUBLE_EQ(p.intensity({0, 0, 1}), 120);
}

TEST(IesSymmetry, BilinearExactForAProfileLinearInBothAngles) {
  // a + bγ + cC + dγC is reproduced exactly by bilinear interpolation, on any (uneven) table.
  auto f = [](double v, double h) { return 300 + 0.7 * v + 0.2 * h + 0.01 * v * h; };
  Spec s;
  s.vertical = {0, 5, 30, 31, 90, 170, 180};
  s.horizontal = {0, 45, 100, 360};
  s.cd = f;
  const IesProfile c = parse(s);
  for (double v = 0; v <= 180; v += 1.7)
    for (double h = 0; h < 360; h += 3.3) EXPECT_NEAR(c.candela_at(v, h), f(v, h), 1e-9 * f(v, h)) << v << " " << h;
  s.type = 2;  // type B, −90..90 both ways
  s.vertical = {-90, -40, 0, 10, 90};
  s.horizontal = {-90, -20, 0, 60, 90};
  s.cd = [](double v, double h) { return 300 + 0.7 * v + 0.2 * h + 0.01 * v * h; };
  const IesProfile b = parse(s);
  for (double v = -90; v <= 90; v += 1.7)
    for (double h = -90; h <= 90; h += 3.3) EXPECT_NEAR(b.candela_at(v, h), f(v, h), 1e-9 * f(v, h)) << v << " " << h;
  EXPECT_EQ(b.candela_at(90.5, 0), 0);
  EXPECT_EQ(b.candela_at(0, -90.5), 0);
}

TEST(IesSymmetry, TypesAAndBSymmetricHalves) {
  Spec s;
  s.type = 3;
  s.vertical = {0, 30, 90};  // |V|
  s.horizontal = {0, 45, 90};  // |H|
  s.cd = [](double v, double h) { return 10 + v + 2 * h; };
  const IesProfile p = parse(s);
  EXPECT_DOUBLE_EQ(p.candela_at(-30, -45), 10 + 30 + 90);
  EXPECT_DOUBLE_EQ(p.candela_at(30, -45), p.candela_at(30, 45));
  EXPECT_DOUBLE_EQ(p.candela_at(-15, 20), p.candela_at(15, 20));
  EXPECT_DOUBLE_EQ(p.intensity(dir_a(-20, 35)), p.intensity(dir_a(20, -35)));
}

// --- The light's frame --------------------------------------------------------------------------

TEST(IesIntensity, TypeCFrame) {
  Spec s;
  s.vertical = {0, 90, 180};
  s.horizontal = {0, 90, 180, 270, 360};
  s.cd = [](double v, double h) { return 1000 + 10 * v + h; };  // every node distinct
  const IesProfile p = parse(s);
  EXPECT_DOUBLE_EQ(p.intensity({0, 0, -1}), 1000);         // nadir: (0, 0)
  EXPECT_DOUBLE_EQ(p.intensity({-0.0, -0.0, -1}), 1000);   // C taken as 0 at the pole, whatever the signs
  EXPECT_DOUBLE_EQ(p.intensity({1, 0, 0}), 1900);          // γ 90, C 0
  EXPECT_DOUBLE_EQ(p.intensity({0, 1, 0}), 1990);          // C 90
  EXPECT_DOUBLE_EQ(p.intensity({-1, 0, 0}), 2080);         // C 180
  EXPECT_DOUBLE_EQ(p.intensity({-1, -0.0, 0}), 2080);
  EXPECT_DOUBLE_EQ(p.intensity({0, -1, 0}), 2170);         // C 270
  EXPECT_DOUBLE_EQ(p.intensity({0, 0, 1}), 2800);          // zenith: γ 180
  EXPECT_DOUBLE_EQ(p.intensity({0, 0, -5}), 1000);         // not unit: same direction
  for (double g = 1; g < 180; g += 11)  // off the poles, where this (unphysical) table depends on C
    for (double c = 0; c < 360; c += 13) EXPECT_NEAR(p.intensity(dir_c(g, c)), p.candela_at(g, c), 1e-9) << g << " " << c;
}

TEST(IesIntensity, TypeBFrame) {
  Spec s;
  s.type = 2;
  s.vertical = {-90, 0, 90};
  s.horizontal = {-90, 0, 90};
  s.cd = [](double v, double h) { return 1000 + 10 * v + h; };
  const IesProfile p = parse(s);
  EXPECT_DOUBLE_EQ(p.intensity({0, 0, -1}), 1000);  // the aim: (0, 0)
  EXPECT_DOUBLE_EQ(p.intensity({1, 0, 0}), 1900);   // V 90 towards +X
  EXPECT_DOUBLE_EQ(p.intensity({-1, 0, 0}), 100);   // V −90
  EXPECT_DOUBLE_EQ(p.intensity({0, -1, 0}), 1090);  // H 90 towards −Y
  EXPECT_DOUBLE_EQ(p.intensity({0, 1, 0}), 910);    // H −90
  EXPECT_EQ(p.intensity({0, 0, 1}), 0);             // behind
  EXPECT_EQ(p.intensity(dir_c(120, 40)), 0);
  for (double v = -90; v <= 90; v += 7)
    for (double h = -81; h <= 81; h += 9) EXPECT_NEAR(p.intensity(dir_b(v, h)), p.candela_at(v, h), 1e-9) << v << " " << h;
}

TEST(IesIntensity, TypeAFrame) {
  Spec s;
  s.type = 3;
  s.vertical = {-90, 0, 90};
  s.horizontal = {-90, 0, 90};
  s.cd = [](double v, double h) { return 1000 + 10 * v + h; };
  const IesProfile p = parse(s);
  EXPECT_DOUBLE_EQ(p.intensity({0, 0, -1}), 1000);
  EXPECT_DOUBLE_EQ(p.intensity({1, 0, 0}), 1900);   // V 90: +X
  EXPECT_DOUBLE_EQ(p.intensity({-1, 0, 0}), 100);
  EXPECT_DOUBLE_EQ(p.intensity({0, -1, 0}), 1090);  // H 90 towards −Y
  EXPECT_DOUBLE_EQ(p.intensity({0, 1, 0}), 910);
  EXPECT_EQ(p.intensity({0, 0, 1}), 0);
  for (double v = -89; v <= 89; v += 7)
    for (double h = -90; h <= 90; h += 9) EXPECT_NEAR(p.intensity(dir_a(v, h)), p.candela_at(v, h), 1e-9) << v << " " << h;
}

// --- Flux ---------------------------------------------------------------------------------------

TEST(IesFlux, IsotropicIsFourPiTimesTheCandela) {
  auto flat = [](double, double) { return 100.0; };
  const std::vector<std::vector<double>> horizontals = {{0}, {0, 90}, {0, 30, 180}, steps(0, 360, 15), {90, 180, 270}};
  for (const auto& h : horizontals) {
    Spec s;
    s.head = "IESNA:LM-63-1995\n";
    s.vertical = {0, 90, 180};
    s.horizontal = h;
    s.cd = flat;
    EXPECT_NEAR(parse(s).flux(), 400 * kPi, 1e-6 * 400 * kPi) << h.size() << " horizontal angles";
    s.vertical = steps(0, 180, 5);
    EXPECT_NEAR(parse(s).flux(), 400 * kPi, 1e-6 * 400 * kPi);
  }
  // Types A and B light the front hemisphere: 200π, whole or from a symmetric half or quadrant.
  for (int type : {2, 3}) {
    for (double v0 : {-90.0, 0.0}) {
      for (double h0 : {-90.0, 0.0}) {
        Spec s;
        s.type = type;
        s.vertical = {v0, 45, 90};
        s.horizontal = {h0, 10, 90};
        s.cd = flat;
        EXPECT_NEAR(parse(s).flux(), 200 * kPi, 1e-6 * 200 * kPi) << type << " " << v0 << " " << h0;
      }
    }
  }
}

TEST(IesFlux, LambertianDownlightIsPiTimesI0) {
  Spec s;
  s.vertical = steps(0, 90, 1);
  s.horizontal = {0, 90};
  s.cd = [](double g, double) { return 1000 * std::cos(g * kDeg); };
  const IesProfile p = parse(s);
  EXPECT_NEAR(p.flux(), kPi * 1000, 1e-4 * kPi * 1000);
  EXPECT_DOUBLE_EQ(p.max_candela(), 1000);
}

TEST(IesFlux, ExactForTheInterpolation) {
  // A table of two vertical angles 0 and 180 with I = 100 at 0 and 0 at 180: interpolated,
  // I = 100 (1 − γ/π), ∫ = 2π · 100 ∫ (1 − γ/π) sin γ dγ = 2π · 100 · (2 − 1) = 200π.
  Spec s;
  s.vertical = {0, 180};
  s.horizontal = {0};
  s.cd = [](double g, double) { return g == 0 ? 100.0 : 0.0; };
  EXPECT_NEAR(parse(s).flux(), 200 * kPi, 1e-6 * 200 * kPi);
}

// --- Malformed and truncated files --------------------------------------------------------------

// A small valid file, one list per line, CR LF as LM-63 writes it; lines are 1-based below.
std::vector<std::string> valid_lines() {
  return {"IESNA:LM-63-2002",                      // 1
          "[TEST] walkrad",                        // 2
          "TILT=INCLUDE",                          // 3
          "1",                                     // 4
          "3",                                     // 5
          "0 45 90",                               // 6
          "1 0.9 0.8",                             // 7
          "1 -1 1 3 2 1 2 0.5 0.4 0.1",            // 8
          "1 1 10",                                // 9
          "0 45 90",                               // 10
          "0 90",                                  // 11
          "100 80 20",                             // 12
          "100 60 10"};                            // 13
}

std::string join(const std::vector<std::string>& lines, const std::string& eol = "\r\n") {
  std::string t;
  for (const std::string& l : lines) t += l + eol;
  return t;
}

TEST(IesBadInput, EveryTruncatedPrefixIsRefused) {
  for (const std::string eol : {"\r\n", "\n"}) {
    const std::string t = join(valid_lines(), eol);
    EXPECT_EQ(parse_ies(t, "ok.ies").candela.size(), 6u);
    for (size_t n = 0; n < t.size(); ++n) {
      try {
        parse_ies(t.substr(0, n), "cut.ies");
        ADD_FAILURE() << "a prefix of " << n << " bytes was accepted";
      } catch (const InputError& e) {
        EXPECT_EQ(e.code(), kExitBadInput) << n << ": " << e.what();
        EXPECT_EQ(e.place().rfind("line ", 0), 0u) << n << ": " << e.what();
        EXPECT_EQ(e.file(), "cut.ies");
      }
    }
  }
  const std::string t = join(valid_lines());
  EXPECT_EQ(refusal(t.substr(0, t.size() - 2)).message(), "truncated: the file ends inside its last line");
  EXPECT_EQ(refusal(t.substr(0, t.find("100 60 10") + 5)).message(),  // cut inside a number
            "truncated: the file ends inside its last line");
}

TEST(IesBadInput, MalformedNumbersAndRulesNameTheLine) {
  struct Case {
    int line;                // the line to replace (1-based)
    std::string replacement;
    int expected_line;
    std::string message;     // a part of the message
    ExitCode code = kExitBadInput;
  };
  const Case cases[] = {
      {12, "100 1.2.3 20", 12, "'1.2.3' is not a number"},
      {12, "100 nan 20", 12, "candela value 2: 'nan' is not a number"},
      {12, "100 inf 20", 12, "'inf' is not a number"},
      {12, "100 1e999 20", 12, "'1e999' is out of range"},
      {13, "100 abc 10", 13, "candela value 5: 'abc' is not a number"},
      {13, "100 -5 10", 13, "candela value 5 is negative"},
      {12, "100 0x10 20", 12, "not a number"},
      {12, "100 80 20 7", 13, "unexpected text after the candela values"},
      {13, "100 60 10 x", 13, "unexpected text"},
      {8, "1 -1 1 0 2 1 2 0.5 0.4 0.1", 8, "the number of vertical angles must be at least 1, not 0"},
      {8, "1 -1 1 3 1000000000 1 2 0.5 0.4 0.1", 8, "the number of horizontal angles (1000000000) exceeds the limit of 10000",
       kExitLimitReached},
      {8, "1 -1 1 5000 5000 1 2 0.5 0.4 0.1", 8, "25000000 candela values exceed the limit of 4000000", kExitLimitReached},
      {8, "1 -1 1 3 2.5 1 2 0.5 0.4 0.1", 8, "must be a whole number"},
      {8, "0 -1 1 3 2 1 2 0.5 0.4 0.1", 8, "the number of lamps must be from 1 to 1000000, not 0"},
      {8, "1 -1 -2 3 2 1 2 0.5 0.4 0.1", 8, "the candela multiplier is negative"},
      {8, "1 -1 1 3 2 4 2 0.5 0.4 0.1", 8, "the photometric type must be from 1 to 3, not 4"},
      {8, "1 -1 1 3 2 1 3 0.5 0.4 0.1", 8, "the units type must be from 1 to 2, not 3"},
      {8, "1 -2 1 3 2 1 2 0.5 0.4 0.1", 8, "the lumens per lamp"},
      {9, "-1 1 10", 9, "the ballast factor is negative"},
      {9, "1 inf 10", 9, "not a number"},
      {10, "0 90 45", 10, "vertical angle 3 (45) does not ascend"},
      {10, "0 45 45", 10, "does not ascend"},
      {10, "0 45 190", 10, "vertical angle 3 (190) is outside 0..180"},
      {10, "10 45 90", 10, "the first vertical angle must be 0 or 90"},
      {10, "0 45 100", 10, "the last vertical angle must be 90 or 180"},
      {11, "0 400", 11, "outside 0..360"},
      {11, "0 270", 11, "the last horizontal angle must be 0, 90, 180 or 360"},
      {11, "10 90", 11, "the first horizontal angle must be 0"},
      {11, "90 180", 11, "270 (starting at 90)"},
      {11, "-10 90", 11, "outside 0..360"},
      {5, "0", 5, "the number of tilt angles must be at least 1"},
      {4, "4", 4, "the lamp-to-luminaire geometry must be from 1 to 3, not 4"},
      {6, "0 90 45", 6, "tilt angle 3 (45) does not ascend"},
      {7, "1 -0.9 0.8", 7, "tilt factor 2 is negative"},
      {3, "TILT=", 3, "TILT= names nothing"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> lines = valid_lines();
    lines[size_t(c.line - 1)] = c.replacement;
    const InputError e = refusal(join(lines));
    EXPECT_EQ(e.place(), "line " + std::to_string(c.expected_line)) << c.replacement << ": " << e.what();
    EXPECT_NE(e.message().find(c.message), std::string::npos) << c.replacement << ": " << e.what();
    EXPECT_EQ(e.code(), c.code) << c.replacement << ": " << e.what();
    EXPECT_EQ(e.file(), "bad.ies");
  }
}

TEST(IesBadInput, TypesAAndBAngleRules) {
  std::vector<std::string> lines = valid_lines();
  lines[7] = "1 -1 1 3 2 2 2 0.5 0.4 0.1";  // type B
  lines[9] = "-90 0 90";
  lines[10] = "0 90";
  EXPECT_EQ(parse_ies(join(lines), "b").photometry, IesProfile::Photometry::B);
  lines[9] = "-90 0 100";
  EXPECT_NE(refusal(join(lines)).message().find("outside -90..90"), std::string::npos);
  lines[9] = "-45 0 90";
  EXPECT_NE(refusal(join(lines)).message().find("the first vertical angle must be -90 or 0"), std::string::npos);
  lines[9] = "-90 0 45";
  EXPECT_NE(refusal(join(lines)).message().find("the last vertical angle must be 90"), std::string::npos);
  lines[9] = "0 45 90";
  lines[10] = "-90 45";
  EXPECT_NE(refusal(join(lines)).message().find("the last horizontal angle must be 90"), std::string::npos);
}

TEST(IesBadInput, MultipliedCandelaMustStayFinite) {
  std::vector<std::string> lines = valid_lines();
  lines[7] = "1 -1 1e300 3 2 1 2 0.5 0.4 0.1";
  lines[11] = "100 1e300 20";
  const InputError e = refusal(join(lines));
  EXPECT_EQ(e.place(), "line 12");
  EXPECT_NE(e.message().find("candela value 2 times the multipliers is out of range"), std::string::npos) << e.what();
}

TEST(IesBadInput, NoTiltLineOrAnEmptyFile) {
  EXPECT_NE(refusal("").message().find("truncated"), std::string::npos);
  const InputError e = refusal("IESNA:LM-63-2002\n[TEST] a\n[MORE] b\n");
  EXPECT_EQ(e.place(), "line 4");
  EXPECT_EQ(e.message(), "truncated: the file ends before its TILT= line");
}

// --- Files --------------------------------------------------------------------------------------

fs::path test_dir() {
  const auto* info = testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(testing::TempDir()) / ("ies-" + std::string(info->name()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(IesRead, ReadsAFile) {
  const fs::path path = test_dir() / "lamp.ies";
  std::ofstream(path, std::ios::binary) << join(valid_lines());
  const IesProfile p = read_ies(path.string());
  EXPECT_EQ(p.source, path.string());
  EXPECT_EQ(p.candela, parse_ies(join(valid_lines()), "x").candela);
  EXPECT_EQ(p.tilt_factors, (std::vector<double>{1, 0.9, 0.8}));
}

TEST(IesRead, MissingFileFolderAndOversizeRefused) {
  const fs::path dir = test_dir();
  for (const fs::path& p : {dir / "missing.ies", dir}) {
    try {
      read_ies(p.string());
      ADD_FAILURE() << p;
    } catch (const InputError& e) {
      EXPECT_EQ(e.code(), kExitBadInput) << e.what();
      EXPECT_EQ(e.file(), p.string());
    }
  }
  const fs::path big = dir / "big.ies";
  {
    std::ofstream out(big, std::ios::binary);
    out << join(valid_lines()) << std::string(size_t(16) << 20, ' ');
  }
  try {
    read_ies(big.string());
    ADD_FAILURE() << "a file over 16 MiB was read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.code(), kExitLimitReached) << e.what();
  }
}

}  // namespace
}  // namespace walkrad
