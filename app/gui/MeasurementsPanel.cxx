#include "MeasurementsPanel.h"

#include "MainActions.h"
#include "VesselMeasureTable.h"

#include <QAction>
#include <QHeaderView>
#include <QLabel>
#include <QTableWidget>
#include <QToolButton>
#include <QVBoxLayout>

#include <cmath>
#include <vector>

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
  for (int outlet : branch.outlets)
  {
    names << QString::number(outlet);
  }
  return names.isEmpty() ? QString::number(branch.branchId) : names.join(", ");
}

/// The rows of the measure table that the panel shows, in the table's order.
std::vector<const bender::VesselMeasure*> PanelMeasures()
{
  std::vector<const bender::VesselMeasure*> shown;
  for (const bender::VesselMeasure& m : bender::VesselMeasureTable())
  {
    if (m.panel)
    {
      shown.push_back(&m);
    }
  }
  return shown;
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
  const std::vector<const bender::VesselMeasure*> shown = PanelMeasures();
  QStringList heldRows;
  QStringList planColumns{ "Outlets" };
  for (const bender::VesselMeasure* m : shown)
  {
    heldRows << QString::fromStdString(bender::MeasureTitle(*m));
    planColumns << QString::fromStdString(m->label) << "after";
  }
  this->Held = new QTableWidget(static_cast<int>(shown.size()), 3, this);
  this->Held->setObjectName("heldTable");
  this->Held->setHorizontalHeaderLabels({ "Before", "Now", "Change" });
  this->Held->setVerticalHeaderLabels(heldRows);
  this->Held->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  this->Held->setEditTriggers(QAbstractItemView::NoEditTriggers);
  this->Held->setMaximumHeight(30 * (static_cast<int>(shown.size()) + 1));
  layout->addWidget(this->Held);

  auto* planTitle = new QLabel("<b>Plan: before / after</b> (each branch, by its outlets)", this);
  planTitle->setWordWrap(true);
  layout->addWidget(planTitle);
  this->Plan = new QTableWidget(0, planColumns.size(), this);
  this->Plan->setObjectName("planTable");
  this->Plan->setHorizontalHeaderLabels(planColumns);
  this->Plan->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  this->Plan->verticalHeader()->hide();
  this->Plan->setEditTriggers(QAbstractItemView::NoEditTriggers);
  QStringList units;
  for (const bender::VesselMeasure* m : shown)
  {
    units << QString::fromStdString(bender::MeasureTitle(*m));
  }
  this->Plan->setToolTip(units.join(", ") +
    "; the bend angle is between the branch's end "
    "directions; after = the committed surface");
  layout->addWidget(this->Plan, 1);
  this->showHeld({}, {});
}

void MeasurementsPanel::showState(const bender::VesselSession& vessels, const QString& state)
{
  this->State->setText(state);
  const std::vector<const bender::VesselMeasure*> shown = PanelMeasures();
  const auto& comparison = vessels.GetComparison();
  const auto& measures = vessels.GetMeasures();
  // Each row: the outlets, then before and after of each measure of the panel.
  auto showRow = [&](int row, const bender::BranchMeasures* b, const bender::BranchMeasures* a)
  {
    const double nan = std::nan("");
    this->Plan->setItem(row, 0, Item(Outlets(b ? *b : *a)));
    int column = 1;
    for (const bender::VesselMeasure* m : shown)
    {
      this->Plan->setItem(row, column++, Item(Number(b ? m->get(*b) : nan, m->decimals)));
      this->Plan->setItem(
        row, column++, a == b ? Item("=") : Item(Number(a ? m->get(*a) : nan, m->decimals)));
    }
  };
  if (comparison)
  {
    this->Plan->setRowCount(static_cast<int>(comparison->pairs.size()));
    int row = 0;
    for (const bender::BranchChange& pair : comparison->pairs)
    {
      showRow(row++,
        pair.beforeIndex >= 0 ? &comparison->before.branches[pair.beforeIndex] : nullptr,
        pair.afterIndex >= 0 ? &comparison->after.branches[pair.afterIndex] : nullptr);
    }
  }
  else
  {
    // Nothing bent: the branches as they are (before = after).
    this->Plan->setRowCount(static_cast<int>(measures.branches.size()));
    int row = 0;
    for (const bender::BranchMeasures& b : measures.branches)
    {
      showRow(row++, &b, &b);
    }
  }
}

void MeasurementsPanel::showHeld(const bender::HeldBranchMeasures& before,
  const bender::HeldBranchMeasures& now)
{
  const double nan = std::nan("");
  int row = 0;
  for (const bender::VesselMeasure* m : PanelMeasures())
  {
    const double b = before.valid ? m->get(before) : nan;
    const double n = now.valid ? m->get(now) : nan;
    this->Held->setItem(row, 0, Item(Number(b, m->decimals)));
    this->Held->setItem(row, 1, Item(Number(n, m->decimals)));
    this->Held->setItem(row, 2, Item(Signed(n - b, m->decimals)));
    ++row;
  }
}
