#include "EclipseList.hpp"

#include "scene/DeltaT.hpp"
#include "scene/Eclipses.hpp"

#include <QComboBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QPushButton>
#include <QSpinBox>
#include <QTableWidget>
#include <QVBoxLayout>

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace umbra::gui {
namespace {


std::vector<std::pair<std::string, double>> contactsOf(double greatest, const std::vector<std::pair<const char*, scene::Contact>>& named) {
  std::vector<std::pair<std::string, double>> out{{"greatest", greatest}};
  for (const auto& [name, c] : named)
    if (c) out.emplace_back(name, *c);
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
  return out;
}

}  // namespace

EclipseList::EclipseList(std::function<void(double)> goToInstant, QWidget* parent)
    : QWidget(parent), goTo(std::move(goToInstant)) {
  this->fromYear = new QSpinBox;
  this->toYear = new QSpinBox;
  for (QSpinBox* year : {this->fromYear, this->toYear}) year->setRange(-2999, 4999);
  this->fromYear->setValue(2024);
  this->toYear->setValue(2027);
  auto* listButton = new QPushButton("List");
  connect(listButton, &QPushButton::clicked, this, [this] {
    try {
      this->list(this->fromYear->value(), this->toYear->value());
    } catch (const std::exception& e) {
      this->status->setText(QString("error: ") + e.what());
    }
  });
  this->table = new QTableWidget(0, 5);
  this->table->setHorizontalHeaderLabels({"Greatest (UT)", "Kind", "Type", "Magnitude", "Saros"});
  this->table->setSelectionBehavior(QAbstractItemView::SelectRows);
  this->table->setSelectionMode(QAbstractItemView::SingleSelection);
  this->table->setEditTriggers(QAbstractItemView::NoEditTriggers);
  this->table->verticalHeader()->setVisible(false);
  this->table->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  connect(this->table, &QTableWidget::itemSelectionChanged, this, [this] { this->rowSelected(); });
  this->contact = new QComboBox;
  this->contact->setToolTip("The instant: greatest eclipse or a contact (P: penumbra, U: umbra)");
  auto* goButton = new QPushButton("Set the time");
  connect(goButton, &QPushButton::clicked, this, [this] { this->goToChosen(); });
  connect(this->table, &QTableWidget::cellDoubleClicked, this, [this] { this->goToChosen(); });
  this->status = new QLabel;
  this->status->setWordWrap(true);

  auto* years = new QHBoxLayout;
  years->addWidget(new QLabel("Years"));
  years->addWidget(this->fromYear);
  years->addWidget(new QLabel("to"));
  years->addWidget(this->toYear);
  years->addWidget(listButton);
  auto* go = new QHBoxLayout;
  go->addWidget(this->contact, 1);
  go->addWidget(goButton);
  auto* layout = new QVBoxLayout(this);
  layout->addLayout(years);
  layout->addWidget(this->table, 1);
  layout->addLayout(go);
  layout->addWidget(this->status);
}

void EclipseList::list(int from, int to) {
  this->fromYear->setValue(from);
  this->toYear->setValue(to);
  char a[32], b[32];
  std::snprintf(a, sizeof a, "%04d-01-01", from);
  std::snprintf(b, sizeof b, "%04d-01-01", to + 1);
  scene::EclipseSearch search;
  search.fromTt = scene::ttFromUt1(scene::parseUtDate(a));
  search.toTt = scene::ttFromUt1(scene::parseUtDate(b));
  std::vector<Row> rows;
  for (const auto& e : scene::findSolarEclipses(search)) {
    Row r;
    r.dateUt = scene::formatJulianDate(scene::ut1FromTt(e.greatestTt, e.deltaTSeconds), 0);
    r.kind = "solar";
    r.type = scene::typeName(e.type);
    r.magnitude = e.magnitude, r.deltaTSeconds = e.deltaTSeconds, r.saros = e.saros;
    r.contacts = contactsOf(e.greatestTt, {{"P1", e.p1}, {"P2", e.p2}, {"U1", e.u1}, {"U2", e.u2}, {"U3", e.u3},
                                           {"U4", e.u4}, {"P3", e.p3}, {"P4", e.p4}});
    rows.push_back(r);
  }
  for (const auto& e : scene::findLunarEclipses(search)) {
    Row r;
    r.dateUt = scene::formatJulianDate(scene::ut1FromTt(e.greatestTt, e.deltaTSeconds), 0);
    r.kind = "lunar";
    r.type = scene::typeName(e.type);
    r.magnitude = e.umbralMagnitude, r.deltaTSeconds = e.deltaTSeconds, r.saros = e.saros;
    r.contacts = contactsOf(e.greatestTt, {{"P1", e.p1}, {"U1", e.u1}, {"U2", e.u2}, {"U3", e.u3}, {"U4", e.u4}, {"P4", e.p4}});
    rows.push_back(r);
  }
  std::sort(rows.begin(), rows.end(), [](const Row& x, const Row& y) { return x.contacts.front().second < y.contacts.front().second; });
  this->eclipses = std::move(rows);
  this->fill();
  this->status->setText(QString("%1 eclipses (lunar magnitudes: umbral)").arg(this->eclipses.size()));
}

void EclipseList::fill() {
  this->table->setRowCount(static_cast<int>(this->eclipses.size()));
  for (int i = 0; i < this->rowCount(); ++i) {
    const Row& r = this->eclipses[static_cast<size_t>(i)];
    const QStringList cells{QString::fromStdString(r.dateUt).replace('T', ' '), QString::fromStdString(r.kind),
                            QString::fromStdString(r.type), QString::number(r.magnitude, 'f', 4), QString::number(r.saros)};
    for (int c = 0; c < cells.size(); ++c) this->table->setItem(i, c, new QTableWidgetItem(cells[c]));
  }
  this->contact->clear();
}

std::optional<int> EclipseList::rowOn(const std::string& date) const {
  for (int i = 0; i < this->rowCount(); ++i)
    if (this->eclipses[static_cast<size_t>(i)].dateUt.compare(0, date.size(), date) == 0) return i;
  return std::nullopt;
}

void EclipseList::rowSelected() {
  this->contact->clear();
  const auto selected = this->table->selectionModel()->selectedRows();
  if (selected.empty()) return;
  for (const auto& [name, tt] : this->eclipses[static_cast<size_t>(selected.front().row())].contacts)
    this->contact->addItem(QString::fromStdString(name));
  this->contact->setCurrentText("greatest");
}

bool EclipseList::choose(int row, const std::string& name) {
  if (row < 0 || row >= this->rowCount()) return false;
  this->table->selectRow(row);
  const int index = this->contact->findText(QString::fromStdString(name));
  if (index < 0) return false;
  this->contact->setCurrentIndex(index);
  this->goToChosen();
  return true;
}

void EclipseList::goToChosen() {
  const auto selected = this->table->selectionModel()->selectedRows();
  if (selected.empty() || this->contact->currentIndex() < 0) return;
  const Row& r = this->eclipses[static_cast<size_t>(selected.front().row())];
  const std::string name = this->contact->currentText().toStdString();
  for (const auto& [contactName, tt] : r.contacts)
    if (contactName == name) {
      this->status->setText(QString::fromStdString("the " + r.kind + " eclipse of " + r.dateUt.substr(0, 10) + " at " + name));
      this->goTo(scene::ut1FromTt(tt, r.deltaTSeconds));
    }
}

}  // namespace umbra::gui
