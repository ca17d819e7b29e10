#include "SweepCandidateTable.h"

#include <QBrush>
#include <QHeaderView>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace
{
using Value = std::function<double(const bender::SweepRow&)>;

/// A column of numbers: its title, decimals shown, and the value of a row (NaN: none).
struct NumberColumn
{
  QString title;
  int decimals;
  Value value;
};

constexpr double NaN = std::numeric_limits<double>::quiet_NaN();

double Solved(const bender::SweepRow& row, double value)
{
  return row.state == "solved" ? value : NaN;
}

QString ParameterTitle(const std::string& parameter)
{
  if (parameter == "fraction")
  {
    return "Fraction";
  }
  return parameter == "radius" ? "Radius (mm)" : "Plan";
}

/// The number columns of `rows`, in summary.csv's order; one split column per outlet.
std::vector<NumberColumn> NumberColumns(const std::vector<bender::SweepRow>& rows)
{
  std::vector<NumberColumn> columns = {
    { "Bend (deg)", 1, [](const bender::SweepRow& r) { return r.measures.bendAngle; } },
    { "Length change (%)", 1, [](const bender::SweepRow& r) { return r.measures.lengthChange; } },
    { "Min radius (mm)", 2, [](const bender::SweepRow& r) { return r.measures.minRadius; } },
    { "Pressure drop (Pa)",
      3,
      [](const bender::SweepRow& r) { return Solved(r, r.pressureDrop); } },
  };
  std::vector<std::string> outlets;
  for (const bender::SweepRow& row : rows)
  {
    for (const bender::SweepOutlet& o : row.outlets)
    {
      if (std::find(outlets.begin(), outlets.end(), o.name) == outlets.end())
      {
        outlets.push_back(o.name);
      }
    }
  }
  for (const std::string& name : outlets)
  {
    columns.push_back({ "Split " + QString::fromStdString(name) + " (%)",
      1,
      [name](const bender::SweepRow& r)
      {
        for (const bender::SweepOutlet& o : r.outlets)
        {
          if (o.name == name)
          {
            return Solved(r, o.splitPercent);
          }
        }
        return NaN;
      } });
  }
  const auto wss = [](double bender::SweepRow::*field)
  {
    return [field](const bender::SweepRow& r)
    { return r.wallShearStress ? Solved(r, r.*field) : NaN; };
  };
  columns.push_back({ "Mean WSS (Pa)", 3, wss(&bender::SweepRow::wssMean) });
  columns.push_back({ "Low-WSS area (mm2)", 1, wss(&bender::SweepRow::lowWssArea) });
  columns.push_back({ "Cells", 0, [](const bender::SweepRow& r) {
                       return Solved(r, static_cast<double>(r.meshCells));
                     } });
  columns.push_back({ "Iterations", 0, [](const bender::SweepRow& r) {
                       return Solved(r, static_cast<double>(r.iterations));
                     } });
  return columns;
}

QTableWidgetItem* NumberItem(double value, int decimals)
{
  auto* item = new QTableWidgetItem(
    std::isfinite(value) ? QString::number(value, 'f', decimals) : QString("-"));
  if (std::isfinite(value))
  {
    item->setData(Qt::UserRole, value);
  }
  item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
  return item;
}
} // namespace

SweepCandidateTable::SweepCandidateTable(QWidget* parent)
  : QTableWidget(parent)
{
  this->setObjectName("sweepTable");
  this->verticalHeader()->hide();
  this->setMinimumHeight(150);
  this->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  this->horizontalHeader()->setStretchLastSection(true);
  this->setEditTriggers(QAbstractItemView::NoEditTriggers);
  this->setSelectionBehavior(QAbstractItemView::SelectRows);
  this->setSelectionMode(QAbstractItemView::SingleSelection);
  this->setToolTip("The sweep's candidates (summary.csv); choose one to see it beside the "
                   "original");
  connect(this,
    &QTableWidget::currentCellChanged,
    this,
    [this](int row, int, int previous, int)
    {
      if (row >= 0 && row != previous)
      {
        emit this->candidateChosen(row);
      }
    });
}

void SweepCandidateTable::setRows(const std::vector<bender::SweepRow>& rows,
  const std::string& parameter)
{
  const std::vector<NumberColumn> numbers = NumberColumns(rows);
  QStringList titles = { "Candidate", ParameterTitle(parameter), "State" };
  for (const NumberColumn& column : numbers)
  {
    titles << column.title;
  }
  titles << "Why not solved";
  const QSignalBlocker quiet(this);
  this->clear();
  this->setColumnCount(titles.size());
  this->setHorizontalHeaderLabels(titles);
  this->setRowCount(static_cast<int>(rows.size()));
  const QBrush grey(QColor(140, 140, 140));
  for (int r = 0; r < static_cast<int>(rows.size()); ++r)
  {
    const bender::SweepRow& row = rows[static_cast<std::size_t>(r)];
    const QString id =
      QString::fromStdString(row.id) + (row.original && row.id != "original" ? " (original)" : "");
    this->setItem(r, 0, new QTableWidgetItem(id));
    this->setItem(r,
      1,
      parameter == "plan" ? new QTableWidgetItem(QString::fromStdString(row.planName))
                          : NumberItem(row.value, parameter == "fraction" ? 3 : 2));
    this->setItem(r, 2, new QTableWidgetItem(QString::fromStdString(row.state)));
    int c = 3;
    for (const NumberColumn& column : numbers)
    {
      this->setItem(r, c++, NumberItem(column.value(row), column.decimals));
    }
    auto* why = new QTableWidgetItem(QString::fromStdString(row.reason));
    why->setToolTip(
      QString::fromStdString(row.log.empty() ? row.reason : row.reason + "\nlog: " + row.log));
    this->setItem(r, c, why);
    if (row.state != "solved")
    {
      for (int k = 0; k < this->columnCount(); ++k)
      {
        this->item(r, k)->setForeground(grey);
      }
    }
  }
  this->setCurrentCell(-1, -1);
}

int SweepCandidateTable::columnOf(const QString& title) const
{
  for (int c = 0; c < this->columnCount(); ++c)
  {
    if (this->horizontalHeaderItem(c) && this->horizontalHeaderItem(c)->text() == title)
    {
      return c;
    }
  }
  return -1;
}
