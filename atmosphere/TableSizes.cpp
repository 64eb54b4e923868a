#include "TableSizes.hpp"

namespace umbra::atmosphere {

std::string sizeText(const int (&size)[2]) { return std::to_string(size[0]) + "x" + std::to_string(size[1]); }

std::string sizeText(const int (&size)[4]) {
  return std::to_string(size[0]) + "," + std::to_string(size[1]) + "," + std::to_string(size[2]) + "," +
         std::to_string(size[3]);
}

std::string brunetonSizesText(const TableSizes& s) {
  return sizeText(s.transmittance) + ", " + sizeText(s.scattering) + ", " + sizeText(s.irradiance) + ", " +
         std::to_string(s.orders) + " orders";
}

}  // namespace umbra::atmosphere
