// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcParameterPanel
 * @brief A stage's parameters as a form whose rows are fields bound to the setters they feed.
 *
 * One generic panel rather than a class per stage: the stages' panels differ only in their rows,
 * and a row keeps its field and the filter setter it feeds side by side (one statement per
 * parameter, where a widget in a builder and its setter in a push method far below used to be
 * two). A builder (tcStagePanels) adds the rows of one filter, so each panel owns its widgets
 * and pushes its parameters to its filter.
 *
 * Apply mode (pipeline parameters): Push sets every row's value on its filter; setting an
 * unchanged value does not modify a filter, so only what changed re-runs. Live mode (view
 * settings, the LOD stage): each change of a field is pushed at once, and Push pushes them all.
 *
 * Each field is named (QObject::objectName) after its row, the filter property it sets, so that
 * Field finds it.
 */
#ifndef tcParameterPanel_h
#define tcParameterPanel_h

#include <QWidget>

#include <functional>
#include <vector>

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QFormLayout;
class QSpinBox;

class tcParameterPanel : public QWidget
{
public:
  enum Mode
  {
    Apply, ///< Push sets the rows' values (the Apply button)
    Live   ///< each change is pushed at once
  };

  tcParameterPanel(Mode mode, QWidget* parent);

  /// A check box showing `value`.
  QCheckBox* AddCheck(const QString& name, bool value, std::function<void(bool)> push);

  /// A spin box from `lo` to `hi` showing `value`.
  QSpinBox* AddInt(const QString& name, int lo, int hi, int value, std::function<void(int)> push);

  /// A spin box from `lo` to `hi` with `decimals` decimals and steps of `step`, showing `value`.
  QDoubleSpinBox* AddDouble(const QString& name, double lo, double hi, int decimals, double step,
    double value, std::function<void(double)> push);

  /// A list of `items` showing item `index`; its push gets the index chosen.
  QComboBox* AddChoice(
    const QString& name, const QStringList& items, int index, std::function<void(int)> push);

  /// A button across the form (no parameter: nothing to push).
  void AddButton(const QString& text, const QString& toolTip, std::function<void()> clicked);

  /// A widget below the form that pushes its own settings (nothing for Push to do), which takes
  /// no room while hidden; the panel owns it.
  void AddWidget(QWidget* widget);

  /// Sets every row's value through its setter.
  void Push() const;

  /// The field of the row `name` (nullptr if there is none of type T).
  template <class T>
  T* Field(const QString& name) const
  {
    return this->findChild<T*>(name);
  }

private:
  void AddRow(const QString& name, QWidget* field, std::function<void()> push);

  Mode PushMode;
  QFormLayout* Form;
  std::vector<std::function<void()>> Pushes;
};

#endif
