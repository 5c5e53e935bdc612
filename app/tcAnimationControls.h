// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcAnimationControls
 * @brief The LOD panel's animation box: which animation of a skinned atlas poses the crowd,
 * play and pause, and a time slider to scrub it, with the time in seconds.
 *
 * The pose lives in tcLODView; this box shows it and changes it. Playing advances the time by
 * the wall-clock time between ticks of a QTimer (not by a fixed step per frame, so that a slow
 * frame does not slow the animation down) and loops over [0, duration]. The box hides itself
 * for an atlas without animations (no skin and rig): there is nothing to play.
 *
 * "Own phase per instance" is a check box rather than always on: a crowd in step is every
 * instance in one pose, which shows what distance alone does to each chart's level and skinned
 * box; the phased crowd (the default) shows what a crowd looks like.
 */
#ifndef tcAnimationControls_h
#define tcAnimationControls_h

#include <QElapsedTimer>
#include <QGroupBox>

class QCheckBox;
class QComboBox;
class QLabel;
class QPushButton;
class QSlider;
class QTimer;
class tcLODView;

class tcAnimationControls : public QGroupBox
{
  Q_OBJECT
public:
  tcAnimationControls(tcLODView* view, QWidget* parent);

  /// Shows the view's animations and pose (after it shows a new atlas): hidden when it has
  /// none, which also stops playing.
  void Sync();

  /// Starts or stops playing (the play button).
  void SetPlaying(bool playing);
  bool IsPlaying() const;

private:
  void BuildRows();
  void Connect();
  void Tick();
  void ShowTime();

  tcLODView* View;
  QComboBox* Animation = nullptr;
  QPushButton* Play = nullptr;
  QSlider* Time = nullptr; ///< milliseconds, 0 .. the duration
  QLabel* TimeText = nullptr;
  QCheckBox* Phased = nullptr;
  QTimer* Timer = nullptr;
  QElapsedTimer Clock; ///< since the last tick
};

#endif
