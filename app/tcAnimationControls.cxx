// SPDX-License-Identifier: BSD-3-Clause
#include "tcAnimationControls.h"

#include "tcLODView.h"

#include <QCheckBox>
#include <QComboBox>
#include <QGridLayout>
#include <QLabel>
#include <QPushButton>
#include <QSignalBlocker>
#include <QSlider>
#include <QTimer>

#include <algorithm>
#include <cmath>

tcAnimationControls::tcAnimationControls(tcLODView* view, QWidget* parent)
  : QGroupBox("Animation", parent)
  , View(view)
  , Timer(new QTimer(this))
{
  this->BuildRows();
  this->Connect();
  // About 60 ticks a second at most; a frame that takes longer delays the next tick.
  this->Timer->setInterval(16);
  this->setVisible(false);
}

void tcAnimationControls::BuildRows()
{
  // The slider a row of its own: the dock is narrow, and a short slider scrubs coarsely.
  auto* grid = new QGridLayout(this);
  this->Animation = new QComboBox(this);
  this->Animation->setObjectName("Animation");
  this->Animation->setToolTip("The animation of the atlas's rig that poses every instance");
  grid->addWidget(this->Animation, 0, 0, 1, 2);
  this->Time = new QSlider(Qt::Horizontal, this);
  this->Time->setObjectName("Time");
  this->Time->setToolTip("The crowd's time in the animation: drag to scrub");
  grid->addWidget(this->Time, 1, 0, 1, 2);
  this->Play = new QPushButton("Play", this);
  this->Play->setObjectName("Play");
  this->Play->setCheckable(true);
  this->Play->setToolTip("Play the animation in a loop, or pause it");
  grid->addWidget(this->Play, 2, 0);
  this->TimeText = new QLabel(this);
  this->TimeText->setObjectName("TimeText");
  this->TimeText->setAlignment(Qt::AlignRight | Qt::AlignVCenter);
  grid->addWidget(this->TimeText, 2, 1);
  this->Phased = new QCheckBox("Own phase per instance", this);
  this->Phased->setObjectName("Phased");
  this->Phased->setChecked(this->View->GetPhased());
  this->Phased->setToolTip("Each instance of a crowd at the time plus a phase of its own, so "
                           "that the crowd does not move in step; off: every instance in one "
                           "pose");
  grid->addWidget(this->Phased, 3, 0, 1, 2);
}

void tcAnimationControls::Connect()
{
  connect(this->Animation, QOverload<int>::of(&QComboBox::currentIndexChanged), this,
    [this](int index)
    {
      this->View->SetAnimation(index);
      this->ShowTime();
    });
  connect(this->Play, &QPushButton::toggled, this, &tcAnimationControls::SetPlaying);
  connect(this->Time, &QSlider::valueChanged, this,
    [this](int milliseconds)
    {
      this->View->SetAnimationTime(1e-3 * milliseconds);
      this->ShowTime();
    });
  connect(this->Phased, &QCheckBox::toggled, this, [this](bool on) { this->View->SetPhased(on); });
  connect(this->Timer, &QTimer::timeout, this, &tcAnimationControls::Tick);
}

void tcAnimationControls::Sync()
{
  const QStringList names = this->View->GetAnimationNames();
  this->setVisible(!names.isEmpty());
  if (names.isEmpty())
  {
    this->SetPlaying(false);
  }
  {
    const QSignalBlocker block(this->Animation);
    QStringList shown;
    for (int i = 0; i < this->Animation->count(); ++i)
    {
      shown << this->Animation->itemText(i);
    }
    if (shown != names)
    {
      this->Animation->clear();
      this->Animation->addItems(names);
    }
    this->Animation->setCurrentIndex(this->View->GetAnimation());
  }
  {
    const QSignalBlocker block(this->Phased);
    this->Phased->setChecked(this->View->GetPhased());
  }
  this->ShowTime();
}

void tcAnimationControls::SetPlaying(bool playing)
{
  playing = playing && this->View->GetAnimationDuration() > 0.0;
  {
    const QSignalBlocker block(this->Play);
    this->Play->setChecked(playing);
  }
  this->Play->setText(playing ? "Pause" : "Play");
  if (playing)
  {
    this->Clock.restart();
    this->Timer->start();
  }
  else
  {
    this->Timer->stop();
  }
}

bool tcAnimationControls::IsPlaying() const
{
  return this->Timer->isActive();
}

void tcAnimationControls::Tick()
{
  // A long gap between ticks (another stage shown, a dialog open) does not jump ahead: at most
  // a tenth of a second a tick.
  const double step = std::min(1e-3 * static_cast<double>(this->Clock.restart()), 0.1);
  const double duration = this->View->GetAnimationDuration();
  if (!this->View->IsShown() || duration <= 0.0)
  {
    return;
  }
  double t = this->View->GetAnimationTime() + step;
  if (t > duration)
  {
    t = std::fmod(t, duration);
  }
  this->View->SetAnimationTime(t);
  this->ShowTime();
}

void tcAnimationControls::ShowTime()
{
  const double duration = this->View->GetAnimationDuration();
  const double t = this->View->GetAnimationTime();
  {
    const QSignalBlocker block(this->Time);
    const int range = static_cast<int>(std::lround(1e3 * duration));
    this->Time->setRange(0, range);
    // A click beside the handle moves a tenth of the animation, not QSlider's 10 ms.
    this->Time->setPageStep(std::max(1, range / 10));
    this->Time->setValue(static_cast<int>(std::lround(1e3 * t)));
  }
  this->TimeText->setText(QString("%1 s / %2 s").arg(t, 0, 'f', 2).arg(duration, 0, 'f', 2));
}
