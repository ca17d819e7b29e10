#include "FlowComparisonTable.h"

#include <QBrush>
#include <QFont>
#include <QHeaderView>

#include <cmath>

FlowComparisonTable::FlowComparisonTable(QWidget* parent)
  : QTableWidget(parent)
{
  this->setObjectName("flowComparison");
  this->setColumnCount(5);
  this->setHorizontalHeaderLabels({ "Quantity", "Original", "Current", "Difference", "Relative" });
  this->verticalHeader()->hide();
  this->horizontalHeader()->setSectionResizeMode(0, QHeaderView::Stretch);
  for (int c = 1; c < 5; ++c)
  {
    this->horizontalHeader()->setSectionResizeMode(c, QHeaderView::ResizeToContents);
  }
  this->setEditTriggers(QAbstractItemView::NoEditTriggers);
  this->setSelectionBehavior(QAbstractItemView::SelectRows);
  this->setToolTip("Current shape against the original: highlighted rows differ notably");
}

void FlowComparisonTable::setComparison(const bender::CfdComparison& comparison)
{
  this->Shown = comparison;
  this->setHorizontalHeaderLabels({ "Quantity",
    QString::fromStdString(comparison.labelA),
    QString::fromStdString(comparison.labelB),
    "Difference",
    "Relative" });
  this->setRowCount(static_cast<int>(comparison.rows.size()));
  int r = 0;
  for (const bender::CfdComparisonRow& row : comparison.rows)
  {
    const int decimals = bender::CfdRowDecimals(row);
    const QString unit = row.unit.empty() ? QString() : " " + QString::fromStdString(row.unit);
    const auto value = [&](const std::optional<double>& v, const std::string& text)
    {
      if (!text.empty())
      {
        return QString::fromStdString(text);
      }
      return v ? QString::fromStdString(bender::FormatCfdValue(v, decimals)) + unit : "-";
    };
    QString relative = "-";
    if (row.relative)
    {
      relative =
        QString("%1%2 %").arg(*row.relative >= 0 ? "+" : "").arg(100.0 * *row.relative, 0, 'f', 1);
    }
    QString difference = "-";
    if (row.difference)
    {
      difference = (*row.difference >= 0 ? "+" : "") +
        QString::fromStdString(bender::FormatCfdValue(row.difference, decimals)) + unit;
    }
    const QString cells[5] = { QString::fromStdString(row.label),
      value(row.a, row.textA),
      value(row.b, row.textB),
      difference,
      relative };
    for (int c = 0; c < 5; ++c)
    {
      auto* item = new QTableWidgetItem(cells[c]);
      if (c > 0)
      {
        item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
      }
      if (row.highlighted)
      {
        QFont bold = item->font();
        bold.setBold(true);
        item->setFont(bold);
        item->setBackground(QBrush(QColor(120, 84, 20)));
        item->setForeground(QBrush(QColor(255, 236, 190)));
      }
      if (!row.note.empty())
      {
        item->setToolTip(QString::fromStdString(row.note));
      }
      this->setItem(r, c, item);
    }
    this->item(r, 0)->setData(Qt::UserRole, QString::fromStdString(row.key));
    ++r;
  }
}

int FlowComparisonTable::rowOf(const QString& key) const
{
  for (int r = 0; r < this->rowCount(); ++r)
  {
    if (this->item(r, 0) && this->item(r, 0)->data(Qt::UserRole).toString() == key)
    {
      return r;
    }
  }
  return -1;
}

int FlowComparisonTable::highlightedRows() const
{
  int n = 0;
  for (const auto& row : this->Shown.rows)
  {
    n += row.highlighted ? 1 : 0;
  }
  return n;
}
