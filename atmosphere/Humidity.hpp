#pragma once
// Hygroscopic aerosol particles in humid air: they take up water, grow, and their
// refractive index moves towards water's (Hess, Koepke & Schult 1998, BAMS 79, 831,
// section 2b, after Hänel 1976). The growth per relative humidity comes from the source's
// table (OPAC's wet mode radii over the dry ones); the index is the volume-weighted mean
// of the dry material and water.
#include <complex>
#include <string>
#include <vector>

namespace umbra::atmosphere {

/// Liquid water's real refractive index at `wavelengthNm` (Hale & Querry 1973, Appl. Opt.
/// 12, 555, 25 C: 300-1000 nm, linear between the rows, the end rows outside). Its
/// imaginary part is below 1e-7 over 300-800 nm and taken as 0.
double waterRefractiveIndexReal(double wavelengthNm);

/// r_wet / r_dry at `relativeHumidity` (0..1) from the source's rows (relativeHumidity
/// increasing in [0, 1), factors >= 1), linear between them; the first row's factor below
/// it, the last's above. Throws std::invalid_argument for rows that are not that (naming
/// the first bad one in the message).
double growthFactor(const std::vector<double>& relativeHumidity, const std::vector<double>& radiusFactor,
                    double humidity);

/// The grown particle's index: water's plus (dry - water) / factor^3, the dry material's
/// share of the volume (OPAC's wet indices: water-soluble at 80 % with factor 1.443,
/// 1.530 - 0.006i dry -> 1.399 - 0.0020i at 550 nm).
std::complex<double> humidRefractiveIndex(std::complex<double> dry, double waterReal, double factor);

}  // namespace umbra::atmosphere
