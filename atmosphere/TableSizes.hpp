#pragma once
// The atmosphere tables' sizes in one place: the defaults, the small set for quick looks and
// tests, and the largest any caller accepts. PrecomputeOptions, the refraction table, the
// filters, the scenes and the commands take them from here.
#include <string>

namespace umbra::atmosphere {

struct TableSizes {
  int transmittance[2];  ///< x_mu x x_r
  int scattering[4];     ///< R, MU (even), MU_S, NU
  int irradiance[2];     ///< x_mu_s x x_r
  int refraction[2];     ///< x_mu x x_r
  int orders;            ///< scattering orders (1: single only)
};

/// What every table is made at unless asked otherwise (Bruneton 2017's sizes, 4 orders;
/// docs/accuracy-vs-speed/atmosphere-tables.md, "Table sizes", says what each costs and buys).
inline constexpr TableSizes kDefaultTableSizes{{256, 64}, {32, 128, 32, 8}, {64, 16}, {512, 256}, 4};
/// Small tables for quick looks and tests: about a second.
inline constexpr TableSizes kSmallTableSizes{{64, 16}, {8, 32, 8, 4}, {16, 4}, {128, 64}, 3};

/// The largest a caller may ask for: a side of a 2D table, an axis of the 4D tables, the
/// orders and the wavelengths. PrecomputeOptions::validate checks them, and the commands'
/// options and the filters' setters take the same bounds.
inline constexpr int kMaxTableSide = 8192;
inline constexpr int kMaxScatteringCells = 1024;
inline constexpr int kMaxOrders = 64;
inline constexpr int kMaxWavelengths = 256;

/// "256x64" (a 2D size), "32,128,32,8" (the scattering size), for help texts and messages.
std::string sizeText(const int (&size)[2]);
std::string sizeText(const int (&size)[4]);
/// "256x64, 32,128,32,8, 64x16, 4 orders": the Bruneton tables of a set.
std::string brunetonSizesText(const TableSizes& sizes);

}  // namespace umbra::atmosphere
