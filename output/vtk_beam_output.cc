#include "output/vtk_beam_output.h"

#include "output/vtk_xml_file.h"

#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkQuad.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <algorithm>
#include <vector>

namespace beamslider
{
  void write_beam_shapes_vtu(const FEBeam &beam, const std::vector<NamedShape> &shapes, const std::string &filename,
                             const std::vector<std::pair<std::string, double>> &field_data,
                             const unsigned int samples_per_element)
  {
    const double L = beam.length();
    const unsigned int n_x = samples_per_element * beam.n_elements() + 1;
    // Each point at the thickness of the element to its right, so that a beam
    // of several sections is drawn with each section's own thickness.
    std::vector<double> h(n_x);
    for (unsigned int i = 0; i < n_x; ++i)
      h[i] = beam.thickness_at(std::min(L * i / (n_x - 1), L));

    vtkNew<vtkPoints> points;
    for (unsigned int i = 0; i < n_x; ++i)
      for (const double z : {-0.5 * h[i], 0.5 * h[i]})
        points->InsertNextPoint(L * i / (n_x - 1), 0., z);

    vtkNew<vtkUnstructuredGrid> grid;
    grid->SetPoints(points);
    for (unsigned int i = 0; i + 1 < n_x; ++i)
      {
        // Counter-clockwise in the x–z plane: bottom-left, bottom-right, top-right, top-left.
        const vtkIdType ids[4] = {vtkIdType(2 * i), vtkIdType(2 * i + 2), vtkIdType(2 * i + 3), vtkIdType(2 * i + 1)};
        grid->InsertNextCell(VTK_QUAD, 4, ids);
      }

    for (const auto &s : shapes)
      {
        vtkNew<vtkDoubleArray> displacement;
        displacement->SetName(s.name.c_str());
        displacement->SetNumberOfComponents(3);
        for (unsigned int i = 0; i < n_x; ++i)
          {
            const FEPointShape p = beam.point_shape(L * i / (n_x - 1));
            double u = 0, w = 0, dw = 0;
            for (unsigned int a = 0; a < 4; ++a)
              {
                w += p.w_values[a] * s.shape[p.w_dofs[a]];
                dw += p.slope_values[a] * s.shape[p.w_dofs[a]];
              }
            for (unsigned int k = 0; k < p.u_dofs.size(); ++k)
              u += p.u_values[k] * s.shape[p.u_dofs[k]];
            for (const double z : {-0.5 * h[i], 0.5 * h[i]})
              {
                const double d[3] = {s.scale * (u - z * dw), 0., s.scale * w};
                displacement->InsertNextTuple(d);
              }
          }
        grid->GetPointData()->AddArray(displacement);

        vtkNew<vtkDoubleArray> scale;
        scale->SetName(("scale_" + s.name).c_str());
        scale->InsertNextValue(s.scale);
        grid->GetFieldData()->AddArray(scale);
      }
    for (const auto &[name, value] : field_data)
      {
        vtkNew<vtkDoubleArray> a;
        a->SetName(name.c_str());
        a->InsertNextValue(value);
        grid->GetFieldData()->AddArray(a);
      }

    // Into memory, then whole into the folder: VTK's own file writing would
    // follow a link at `filename`.
    write_vtk_xml<vtkXMLUnstructuredGridWriter>(*grid, filename);
  }
} // namespace beamslider
