#include "MeasurementsPanel.h"

#include "MainActions.h"

#include <QAction>
#include <QHeaderView>
#include <QLabel>
#include <QTableWidget>
#include <QToolButton>
#include <QVBoxLayout>

#include <cmath>
#include <sstream>

namespace
{
QTableWidgetItem* Item(const QString& text)
{
  auto* item = new QTableWidgetItem(text);
  item->setFlags(Qt::ItemIsEnabled | Qt::ItemIsSelectable);
  item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
  return item;
}

QString Number(double value, int decimals)
{
  return std::isfinite(value) ? QString::number(value, 'f', decimals) : QString("-");
}

QString Signed(double value, int decimals)
{
  return std::isfinite(value) ? (value >= 0 ? "+" : "") + QString::number(value, 'f', decimals)
                              : QString("-");
}

/// "1" or "1, 2": the outlets a branch leads to (its identity across before and after).
QString Outlets(const bender::BranchMeasures& branch)
{
  QStringList names;
  for (int outlet : branch.Outlets)
  {
    names << QString::number(outlet);
  }
  return names.isEmpty() ? QString::number(branch.BranchId) : names.join(", ");
}
} // namespace

MeasurementsPanel::MeasurementsPanel(MainActions* actions, QWidget* parent)
  : QWidget(parent)
{
  this->setObjectName("measurementsPanel");
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(ActionButton(actions->ShowCenterline, this, "showCenterlineButton"));
  this->State = new QLabel("No centerlines: open a vessel surface", this);
  this->State->setObjectName("centerlineState");
  this->State->setWordWrap(true);
  layout->addWidget(this->State);

  auto* heldTitle = new QLabel("<b>Branch under the ribbon</b> (between its ends)", this);
  heldTitle->setWordWrap(true);
  layout->addWidget(heldTitle);
  this->Held = new QTableWidget(3, 3, this);
  this->Held->setObjectName("heldTable");
  this->Held->setHorizontalHeaderLabels({ "Before", "Now", "Change" });
  this->Held->setVerticalHeaderLabels({ "Length (mm)", "Bend angle (deg)", "Min radius (mm)" });
  this->Held->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  this->Held->setEditTriggers(QAbstractItemView::NoEditTriggers);
  this->Held->setMaximumHeight(120);
  layout->addWidget(this->Held);

  auto* planTitle = new QLabel("<b>Plan: before / after</b> (each branch, by its outlets)", this);
  planTitle->setWordWrap(true);
  layout->addWidget(planTitle);
  this->Plan = new QTableWidget(0, 7, this);
  this->Plan->setObjectName("planTable");
  this->Plan->setHorizontalHeaderLabels(
    { "Outlets", "Length", "after", "Bend", "after", "Min R", "after" });
  this->Plan->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  this->Plan->verticalHeader()->hide();
  this->Plan->setEditTriggers(QAbstractItemView::NoEditTriggers);
  this->Plan->setToolTip("Length and minimal radius in mm, bend angle (between the branch's end "
                         "directions) in degrees; after = the committed surface");
  layout->addWidget(this->Plan, 1);
  this->showHeld({}, {});
}

void MeasurementsPanel::showState(const bender::VesselSession& vessels, const QString& state)
{
  this->State->setText(state);
  const auto& comparison = vessels.GetComparison();
  const auto& measures = vessels.GetMeasures();
  if (comparison)
  {
    this->Plan->setRowCount(static_cast<int>(comparison->Pairs.size()));
    int row = 0;
    for (const bender::BranchChange& pair : comparison->Pairs)
    {
      const bender::BranchMeasures* b =
        pair.BeforeIndex >= 0 ? &comparison->Before.Branches[pair.BeforeIndex] : nullptr;
      const bender::BranchMeasures* a =
        pair.AfterIndex >= 0 ? &comparison->After.Branches[pair.AfterIndex] : nullptr;
      const double nan = std::nan("");
      this->Plan->setItem(row, 0, Item(Outlets(b ? *b : *a)));
      this->Plan->setItem(row, 1, Item(Number(b ? b->Length : nan, 1)));
      this->Plan->setItem(row, 2, Item(Number(a ? a->Length : nan, 1)));
      this->Plan->setItem(row, 3, Item(Number(b ? b->BendAngle : nan, 1)));
      this->Plan->setItem(row, 4, Item(Number(a ? a->BendAngle : nan, 1)));
      this->Plan->setItem(row, 5, Item(Number(b ? b->MinRadius : nan, 2)));
      this->Plan->setItem(row, 6, Item(Number(a ? a->MinRadius : nan, 2)));
      ++row;
    }
  }
  else
  {
    // Nothing bent: the branches as they are (before = after).
    this->Plan->setRowCount(static_cast<int>(measures.Branches.size()));
    int row = 0;
    for (const bender::BranchMeasures& b : measures.Branches)
    {
      this->Plan->setItem(row, 0, Item(Outlets(b)));
      this->Plan->setItem(row, 1, Item(Number(b.Length, 1)));
      this->Plan->setItem(row, 2, Item("="));
      this->Plan->setItem(row, 3, Item(Number(b.BendAngle, 1)));
      this->Plan->setItem(row, 4, Item("="));
      this->Plan->setItem(row, 5, Item(Number(b.MinRadius, 2)));
      this->Plan->setItem(row, 6, Item("="));
      ++row;
    }
  }
}

void MeasurementsPanel::showHeld(const bender::HeldBranchMeasures& before,
  const bender::HeldBranchMeasures& now)
{
  const double nan = std::nan("");
  const double b[3] = { before.Valid ? before.Length : nan,
    before.Valid ? before.BendAngle : nan,
    before.Valid ? before.MinRadius : nan };
  const double n[3] = {
    now.Valid ? now.Length : nan, now.Valid ? now.BendAngle : nan, now.Valid ? now.MinRadius : nan
  };
  const int decimals[3] = { 1, 1, 2 };
  for (int row = 0; row < 3; ++row)
  {
    this->Held->setItem(row, 0, Item(Number(b[row], decimals[row])));
    this->Held->setItem(row, 1, Item(Number(n[row], decimals[row])));
    this->Held->setItem(row, 2, Item(Signed(n[row] - b[row], decimals[row])));
  }
}
