// SPDX-License-Identifier: BSD-3-Clause
#include "tcColorMaps.h"

#include <vtkDataArray.h>
#include <vtkLookupTable.h>
#include <vtkMath.h>
#include <vtkObjectFactory.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>
#include <vector>

vtkStandardNewMacro(tcColorMaps);

void tcColorMaps::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}

void tcColorMaps::DivergingColors(vtkLookupTable* lut, vtkDataArray* values, int component)
{
  std::vector<double> magnitudes(values ? values->GetNumberOfTuples() : 0);
  for (size_t i = 0; i < magnitudes.size(); ++i)
  {
    magnitudes[i] = std::abs(values->GetComponent(static_cast<vtkIdType>(i), component));
  }
  double limit = 1.0;
  if (!magnitudes.empty())
  {
    const size_t k = std::min(magnitudes.size() - 1, magnitudes.size() * 95 / 100);
    std::nth_element(magnitudes.begin(), magnitudes.begin() + k, magnitudes.end());
    limit = magnitudes[k] > 0.0 && std::isfinite(magnitudes[k]) ? magnitudes[k] : 1.0;
  }
  lut->SetNumberOfTableValues(256);
  lut->SetTableRange(-limit, limit);
  for (int i = 0; i < 256; ++i)
  {
    const double t = i / 255.0;
    const double s = t < 0.5 ? t / 0.5 : (t - 0.5) / 0.5;
    if (t < 0.5)
    {
      lut->SetTableValue(i, 0.23 + 0.77 * s, 0.30 + 0.70 * s, 0.75 + 0.25 * s, 1.0);
    }
    else
    {
      lut->SetTableValue(i, 1.0 - 0.29 * s, 1.0 - 0.98 * s, 1.0 - 0.85 * s, 1.0);
    }
  }
  lut->Build();
}

void tcColorMaps::LabelColors(vtkLookupTable* lut, vtkDataArray* values)
{
  const int count = values ? std::max(1, static_cast<int>(values->GetRange()[1]) + 1) : 1;
  lut->SetNumberOfTableValues(count);
  lut->SetTableRange(0, std::max(1, count - 1));
  for (int i = 0; i < count; ++i)
  {
    double rgb[3];
    vtkMath::HSVToRGB(std::fmod(i * 0.618033988749895, 1.0), 0.55, 0.95, rgb, rgb + 1, rgb + 2);
    lut->SetTableValue(i, rgb[0], rgb[1], rgb[2], 1.0);
  }
  lut->Build();
}

void tcColorMaps::RangeColors(vtkLookupTable* lut, vtkDataArray* values, int component)
{
  double range[2] = { 0.0, 1.0 };
  if (values)
  {
    values->GetRange(range, component);
  }
  if (range[1] <= range[0])
  {
    range[1] = range[0] + 1.0;
  }
  lut->SetNumberOfTableValues(256);
  lut->SetHueRange(0.667, 0.0);
  lut->SetSaturationRange(1.0, 1.0);
  lut->SetValueRange(1.0, 1.0);
  lut->SetTableRange(range);
  lut->ForceBuild();
}

void tcColorMaps::NormalColors(vtkDataArray* normals, vtkUnsignedCharArray* colors)
{
  colors->SetNumberOfComponents(3);
  colors->SetNumberOfTuples(normals->GetNumberOfTuples());
  for (vtkIdType t = 0; t < normals->GetNumberOfTuples(); ++t)
  {
    double n[3];
    normals->GetTuple(t, n);
    const bool empty = n[0] == 0 && n[1] == 0 && n[2] == 0;
    for (int c = 0; c < 3; ++c)
    {
      colors->SetTypedComponent(t, c,
        static_cast<unsigned char>(empty ? 40 : 127.5 + 127 * std::max(-1.0, std::min(1.0, n[c]))));
    }
  }
}
