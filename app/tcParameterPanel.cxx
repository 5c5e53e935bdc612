// SPDX-License-Identifier: BSD-3-Clause
#include "tcParameterPanel.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QPushButton>
#include <QSpinBox>
#include <QVBoxLayout>

#include <utility>

tcParameterPanel::tcParameterPanel(Mode mode, QWidget* parent)
  : QWidget(parent)
  , PushMode(mode)
  , Form(new QFormLayout)
{
  // The form in a column, so that a widget below it (AddWidget) takes no room while hidden: a
  // hidden row of a QFormLayout keeps its spacing.
  auto* column = new QVBoxLayout(this);
  column->addLayout(this->Form);
}

void tcParameterPanel::AddRow(const QString& name, QWidget* field, std::function<void()> push)
{
  field->setObjectName(name);
  this->Form->addRow(name, field);
  this->Pushes.push_back(std::move(push));
}

QCheckBox* tcParameterPanel::AddCheck(
  const QString& name, bool value, std::function<void(bool)> push)
{
  auto* field = new QCheckBox(this);
  field->setChecked(value);
  this->AddRow(name, field, [field, push]() { push(field->isChecked()); });
  if (this->PushMode == Live)
  {
    connect(field, &QCheckBox::toggled, this, push);
  }
  return field;
}

QSpinBox* tcParameterPanel::AddInt(
  const QString& name, int lo, int hi, int value, std::function<void(int)> push)
{
  auto* field = new QSpinBox(this);
  field->setRange(lo, hi);
  field->setValue(value);
  this->AddRow(name, field, [field, push]() { push(field->value()); });
  if (this->PushMode == Live)
  {
    connect(field, QOverload<int>::of(&QSpinBox::valueChanged), this, push);
  }
  return field;
}

QDoubleSpinBox* tcParameterPanel::AddDouble(const QString& name, double lo, double hi, int decimals,
  double step, double value, std::function<void(double)> push)
{
  // Decimals first: the range and the value are rounded to them.
  auto* field = new QDoubleSpinBox(this);
  field->setDecimals(decimals);
  field->setRange(lo, hi);
  field->setSingleStep(step);
  field->setValue(value);
  this->AddRow(name, field, [field, push]() { push(field->value()); });
  if (this->PushMode == Live)
  {
    connect(field, QOverload<double>::of(&QDoubleSpinBox::valueChanged), this, push);
  }
  return field;
}

QComboBox* tcParameterPanel::AddChoice(
  const QString& name, const QStringList& items, int index, std::function<void(int)> push)
{
  auto* field = new QComboBox(this);
  field->addItems(items);
  field->setCurrentIndex(index);
  this->AddRow(name, field, [field, push]() { push(field->currentIndex()); });
  if (this->PushMode == Live)
  {
    connect(field, QOverload<int>::of(&QComboBox::currentIndexChanged), this, push);
  }
  return field;
}

void tcParameterPanel::AddButton(
  const QString& text, const QString& toolTip, std::function<void()> clicked)
{
  auto* button = new QPushButton(text, this);
  button->setToolTip(toolTip);
  this->Form->addRow(button);
  connect(button, &QPushButton::clicked, this, std::move(clicked));
}

void tcParameterPanel::AddWidget(QWidget* widget)
{
  widget->setParent(this);
  static_cast<QVBoxLayout*>(this->layout())->addWidget(widget);
}

void tcParameterPanel::Push() const
{
  for (const std::function<void()>& push : this->Pushes)
  {
    push();
  }
}
