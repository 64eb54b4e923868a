#pragma once
// The "Eclipses" panel: the solar and lunar eclipses of a span of years (scene::Eclipses),
// one row each (date, kind, type, magnitude, Saros); choosing one and a contact moves the
// scene's time there.
#include <QWidget>

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

class QComboBox;
class QLabel;
class QSpinBox;
class QTableWidget;

namespace umbra::gui {

class EclipseList : public QWidget {
public:
  /// `goTo` receives the chosen instant as a UT1 Julian date.
  explicit EclipseList(std::function<void(double ut1Jd)> goTo, QWidget* parent = nullptr);

  /// Lists the eclipses from the start of `fromYear` to the end of `toYear` (both kinds).
  /// Throws std::invalid_argument for a span the search refuses.
  void list(int fromYear, int toYear);
  int rowCount() const { return static_cast<int>(this->eclipses.size()); }
  /// The row whose greatest eclipse falls on `date` (UT, YYYY-MM-DD), if any.
  std::optional<int> rowOn(const std::string& date) const;
  /// Selects `row` and `contact` ("greatest", "P1", "U2"...) and goes there; false when the
  /// eclipse has no such contact.
  bool choose(int row, const std::string& contact);

private:
  struct Row {
    std::string dateUt, kind, type;
    double magnitude = 0.0, deltaTSeconds = 0.0;
    int saros = 0;
    std::vector<std::pair<std::string, double>> contacts;  // name, TT, in time order
  };
  void fill();
  void rowSelected();  // the contact list follows the row
  void goToChosen();

  std::function<void(double)> goTo;
  std::vector<Row> eclipses;
  QSpinBox* fromYear = nullptr;
  QSpinBox* toYear = nullptr;
  QTableWidget* table = nullptr;
  QComboBox* contact = nullptr;
  QLabel* status = nullptr;
};

}  // namespace umbra::gui
