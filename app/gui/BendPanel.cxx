#include "BendPanel.h"

#include "MainActions.h"
#include "PlanSummary.h"

#include <QAction>
#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QLabel>
#include <QToolButton>
#include <QVBoxLayout>

#include <cmath>

BendPanel::BendPanel(MainActions* actions, QWidget* parent)
  : QWidget(parent)
  , Actions(actions)
{
  auto* layout = new QVBoxLayout(this);
  auto* form = new QFormLayout;
  layout->addLayout(form);

  this->Radius = new QDoubleSpinBox(this);
  this->Radius->setObjectName("radius");
  this->Radius->setRange(0.01, 1000.0);
  this->Radius->setDecimals(2);
  this->Radius->setSuffix(" mm");
  this->Radius->setToolTip("Radius R of the region of influence around the initial wire");
  form->addRow("Radius R", this->Radius);
  this->MinimumRadius = new QLabel("r_min: no ribbon placed", this);
  this->MinimumRadius->setToolTip("Smallest arc radius of the ribbon's wire (initial or final, "
                                  "whichever is smaller): R >= r_min risks space inversion "
                                  "(paper 3.8)");
  this->MinimumRadius->setObjectName("minimumRadius");
  this->MinimumRadius->setWordWrap(true);
  this->MinimumRadius->setAlignment(Qt::AlignLeft | Qt::AlignTop);
  // The r_min line and the space-inversion warning's lines are reserved: the warning appears
  // mid-grab, and the buttons below must not move under the pointer.
  this->MinimumRadius->setMinimumHeight(6 * this->MinimumRadius->fontMetrics().lineSpacing());
  form->addRow("", this->MinimumRadius);

  this->Decay = new QComboBox(this);
  this->Decay->setObjectName("decay");
  this->Decay->addItems({ "Bell", "Plateau" });
  this->Decay->setToolTip("How the warp fades from the wire to R: bell (smooth everywhere) or "
                          "plateau (the held part moves as a whole, then fades)");
  form->addRow("Decay", this->Decay);
  this->Plateau = new QDoubleSpinBox(this);
  this->Plateau->setObjectName("plateau");
  this->Plateau->setRange(0.0, 0.95);
  this->Plateau->setSingleStep(0.05);
  this->Plateau->setToolTip("Share of R that moves fully with the ribbon (plateau decay)");
  form->addRow("Plateau width", this->Plateau);
  this->ReverseScrews = new QCheckBox("Reverse screws (paper 3.8)", this);
  this->ReverseScrews->setObjectName("reverseScrews");
  this->ReverseScrews->setEnabled(false);
  this->ReverseScrews->setToolTip("Enabled when the screws flipped during the bend");
  form->addRow("", this->ReverseScrews);
  this->Subdivide = new QCheckBox("Subdivide at release", this);
  this->Subdivide->setObjectName("subdivide");
  this->Subdivide->setToolTip(
    "At release, split the triangles that the warp stretched beyond the tolerance");
  form->addRow("", this->Subdivide);
  this->Tolerance = new QDoubleSpinBox(this);
  this->Tolerance->setObjectName("tolerance");
  this->Tolerance->setRange(0.001, 10.0);
  this->Tolerance->setDecimals(3);
  this->Tolerance->setSuffix(" mm");
  this->Tolerance->setToolTip("Largest distance (mm) between the exact warp and the subdivided "
                              "surface at a triangle's edge midpoint");
  form->addRow("Subdivision tolerance", this->Tolerance);
  this->MaxNarrowing = new QDoubleSpinBox(this);
  this->MaxNarrowing->setObjectName("maxNarrowing");
  this->MaxNarrowing->setRange(0.0, 50.0);
  this->MaxNarrowing->setDecimals(1);
  this->MaxNarrowing->setSingleStep(1.0);
  this->MaxNarrowing->setSuffix(" %");
  this->MaxNarrowing->setSpecialValueText("off");
  this->MaxNarrowing->setValue(100.0 * bender::LumenGuardOptions{}.maxNarrowing);
  this->MaxNarrowing->setToolTip(
    "Lumen guard: a bend that narrows a branch it moved (its minimal inscribed radius along "
    "the centerline) by more than this is held before it is committed; 0 turns it off");
  form->addRow("Lumen guard: max narrowing", this->MaxNarrowing);

  // The gesture buttons show the window's shared actions (menus and keys do the same).
  layout->addWidget(ActionButton(actions->PlaceRibbon, this, "placeRibbon"));
  layout->addWidget(ActionButton(actions->Grab, this, "grab"));
  layout->addWidget(ActionButton(actions->CancelBend, this, "cancelBend"));
  this->State = new QLabel(this);
  this->State->setObjectName("bendState");
  this->State->setWordWrap(true);
  layout->addWidget(this->State);
  layout->addStretch(1);

  this->setParameters(bender::WarpParameters{});
  auto changed = [this]()
  {
    if (!this->Updating)
    {
      this->Plateau->setEnabled(this->Decay->currentIndex() == 1);
      this->Tolerance->setEnabled(this->Subdivide->isChecked());
      emit this->parametersChanged();
    }
  };
  connect(this->Radius, QOverload<double>::of(&QDoubleSpinBox::valueChanged), this, changed);
  connect(this->Decay, QOverload<int>::of(&QComboBox::currentIndexChanged), this, changed);
  connect(this->Plateau, QOverload<double>::of(&QDoubleSpinBox::valueChanged), this, changed);
  connect(this->ReverseScrews, &QCheckBox::toggled, this, changed);
  connect(this->Subdivide, &QCheckBox::toggled, this, changed);
  connect(this->Tolerance, QOverload<double>::of(&QDoubleSpinBox::valueChanged), this, changed);
  connect(this->MaxNarrowing,
    QOverload<double>::of(&QDoubleSpinBox::valueChanged),
    this,
    &BendPanel::lumenGuardChanged);
}

bender::LumenGuardOptions BendPanel::lumenGuard() const
{
  bender::LumenGuardOptions options;
  options.enabled = this->MaxNarrowing->value() > 0.0;
  options.maxNarrowing = this->MaxNarrowing->value() / 100.0;
  return options;
}

void BendPanel::setMaxNarrowing(double percent)
{
  this->MaxNarrowing->setValue(percent);
}

bender::WarpParameters BendPanel::parameters() const
{
  bender::WarpParameters p;
  p.radius = this->Radius->value();
  p.decay.shape =
    this->Decay->currentIndex() == 1 ? bender::DecayShape::Plateau : bender::DecayShape::Bell;
  p.decay.plateau = this->Plateau->value();
  p.reverseScrews = this->ReverseScrews->isChecked();
  p.subdivide = this->Subdivide->isChecked();
  p.subdivisionTolerance = this->Tolerance->value();
  return p;
}

void BendPanel::setParameters(const bender::WarpParameters& p)
{
  this->Updating = true;
  this->Radius->setValue(p.radius);
  this->Decay->setCurrentIndex(p.decay.shape == bender::DecayShape::Plateau ? 1 : 0);
  this->Plateau->setValue(p.decay.plateau);
  this->Plateau->setEnabled(p.decay.shape == bender::DecayShape::Plateau);
  this->ReverseScrews->setChecked(p.reverseScrews);
  this->Subdivide->setChecked(p.subdivide);
  this->Tolerance->setValue(p.subdivisionTolerance);
  this->Tolerance->setEnabled(p.subdivide);
  this->Updating = false;
}

void BendPanel::showState(const bender::BenderSession& session, bool placingRibbon)
{
  const bool grabbed = session.GetState() == bender::GrabState::Grabbed;
  const bool busy = session.IsBusy();
  this->Actions->Grab->setText(grabbed ? "Release (G)" : "Grab (G, or hold Space)");
  this->Actions->Grab->setEnabled(session.HasSurface() && !busy);
  this->Actions->CancelBend->setEnabled((grabbed || placingRibbon) && !busy);
  this->Actions->PlaceRibbon->setEnabled(session.HasSurface() && !grabbed && !busy);
  // The toggle is offered once a flip occurred, and stays so that it can be turned back off.
  this->ReverseScrews->setEnabled(
    (grabbed && session.GetFlipOccurred()) || this->ReverseScrews->isChecked());
  // The one r_min of the session (the status bar's warning quotes the same value): the smaller
  // of the initial and final wire's while grabbed, the placed ribbon's otherwise, cleared with
  // the ribbon.
  {
    const double rmin = session.GetMinimumRadius();
    // A straight wire has an infinite r_min; a nearly straight one an absurdly large one.
    QString text = !session.GetRibbon() && !grabbed ? QString("r_min: no ribbon placed")
      : (std::isfinite(rmin) && rmin < 1e6)         ? QString("r_min = %1 mm").arg(rmin, 0, 'f', 2)
                                                    : QString("r_min: none (straight wire)");
    if (session.GetSpaceInversionRisk())
    {
      text += "\nWarning: " + QString::fromStdString(session.GetSpaceInversionWarning());
      this->MinimumRadius->setStyleSheet("color: #d33;");
    }
    else
    {
      this->MinimumRadius->setStyleSheet("");
    }
    this->MinimumRadius->setText(text);
  }
  QString state;
  switch (session.GetState())
  {
    case bender::GrabState::Idle:
      state = !session.HasSurface() ? "Load or segment a surface"
        : session.GetRibbon()       ? "Idle: ribbon placed; grab (G) to bend"
                                    : "Idle: place the ribbon (P), then grab";
      break;
    case bender::GrabState::Grabbed:
      state =
        QString("Grabbed: %1 points bound; drag the handles").arg(session.GetNumberOfBoundPoints());
      if (!session.GetLiveProblem().empty())
      {
        state += QString("\nNot applied: ") + QString::fromStdString(session.GetLiveProblem());
      }
      break;
    case bender::GrabState::Released:
      state =
        QString("Released: %1").arg(QString::fromStdString(bender::PlanSummary(session.GetPlan())));
      break;
  }
  this->State->setText(state);
}
