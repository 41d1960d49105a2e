// A VTK XML data set (.vtu, .vtp) as a checked result file: VTK writes it
// into memory, write_text_file puts it whole into the folder (a temporary
// renamed into place: never through a link, never half a file), so that a
// failure of VTK or of the disk is an OutputError naming the file and the
// reason (io/output_file.h).
#pragma once

#include "io/output_file.h"

#include <vtkNew.h>

#include <string>

namespace beamslider
{
  template <class Writer, class Data>
  void write_vtk_xml(Data &data, const std::string &filename)
  {
    vtkNew<Writer> writer;
    writer->WriteToOutputStringOn();
    writer->SetInputData(&data);
    writer->SetDataModeToAppended();
    if (writer->Write() != 1)
      throw OutputError("result file '" + filename + "' could not be written: VTK's writer failed (error code " +
                        std::to_string(writer->GetErrorCode()) + ")");
    write_text_file(filename, writer->GetOutputString());
  }
} // namespace beamslider
