// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class tcStagePipeline
 * @brief trichart-viewer's TriChart pipeline, without a window: its filters, running a stage
 * with abort, and the sliver retry.
 *
 * The pipeline is tcMeshReader -> tcMeshPreparation -> tcCurvature -> tcSpectralClustering ->
 * tcFeatureRefinement -> tcBaseComplex -> tcPathTracing -> tcGeometryImages ->
 * tcGeometryImageMesh -> tcSurfaceDistance (against the prepared mesh). Each stage of tcStage is
 * the update of one filter (StageAlgorithm); the VTK pipeline's modified times decide what
 * re-runs, so a face sets the filters' parameters and runs the stage it shows.
 *
 * An atlas file (.exr, tcAtlasReader) can be opened instead of a mesh: it feeds the atlas and
 * reconstruction stages, the stages before them are unavailable (there is no input mesh) and
 * the reconstruction is not measured (there is nothing to measure against).
 *
 * The vertices of a reconstruction are samples of the input surface, so their own distance to it
 * is float rounding (about 1e-7 of the diagonal): the error lies inside the triangles. The
 * reconstruction is therefore measured with each triangle split in 16
 * (vtkLinearSubdivisionFilter: the same flat surface), which puts distance samples inside every
 * triangle; its own edges are extracted apart, to be drawn over it as lines.
 *
 * Retry policy (Run): when path tracing fails because the parameterization is too thin to trace
 * (tcPathTracing::GetUntraceable) and RemoveSlivers is off, the pipeline turns RemoveSlivers on
 * and runs again, as `trichart build` does, and keeps a note that says so (GetNote).
 *
 * No Qt: messages are UTF-8 std::string. A face follows a run through the progress callback (the
 * running filter's class name and its progress, 0 to 1) and cancels it with Abort (from that
 * callback, which is where a face gets to handle its Cancel button).
 */
#ifndef tcStagePipeline_h
#define tcStagePipeline_h

#include <vtkNew.h>

#include <functional>
#include <string>
#include <vector>

class tcAtlasReader;
class tcAtlasWriter;
class tcGLTFWriter;
class tcMeshWriter;
class tcBaseComplex;
class tcCurvature;
class tcFeatureRefinement;
class tcGeometryImageMesh;
class tcGeometryImages;
class tcMeshPreparation;
class tcMeshReader;
class tcPathTracing;
class tcSpectralClustering;
class tcSurfaceDistance;
class vtkAlgorithm;
class vtkExtractEdges;
class vtkLinearSubdivisionFilter;
class vtkMultiBlockDataSet;
class vtkObject;
class vtkPolyData;

/// What a stage shows, taken from the pipeline's outputs (nullptr where the stage has none).
struct tcStageOutput
{
  vtkPolyData* Surface = nullptr; ///< the surface drawn
  /// Crest lines, cluster boundaries, feature lines, base edges, paths (each stage's port 1; the
  /// base complex's edges), or the reconstruction's own edges.
  vtkPolyData* Lines = nullptr;
  vtkPolyData* Corners = nullptr; ///< the corner points of the features stage
  /// What the summary counts: the surface, except for the reconstruction, counted as rebuilt
  /// (not split for the distance colours).
  vtkPolyData* Counted = nullptr;
  vtkMultiBlockDataSet* Atlas = nullptr; ///< the atlas, built or read
};

class tcStagePipeline
{
public:
  tcStagePipeline();
  ~tcStagePipeline();
  tcStagePipeline(const tcStagePipeline&) = delete;
  tcStagePipeline& operator=(const tcStagePipeline&) = delete;

  /// True if `path` is opened as an atlas (.exr, or a file tcAtlasReader recognises).
  static bool IsAtlasFile(const std::string& path);

  /// Feeds the pipeline with the mesh or atlas file `path` (UTF-8) and forgets the last file's
  /// note. Re-connecting the same output is no change, so switching files of one kind re-runs
  /// nothing that does not depend on the file.
  void Open(const std::string& path);

  /// The open file is an atlas: there is no input mesh.
  bool HasAtlasFile() const { return this->AtlasFile; }

  /// False for the stages before the atlas while an atlas file is open (and for no stage).
  bool StageAvailable(int stage) const;

  /// The filter whose update runs `stage` (a tcStage).
  vtkAlgorithm* StageAlgorithm(int stage) const;

  /// The filter whose output is the atlas: tcGeometryImages, or tcAtlasReader for an atlas file.
  vtkAlgorithm* AtlasSource() const;

  /// The outputs `stage` shows, after a successful Run of its StageAlgorithm (updates the edge
  /// extractors the base complex and the reconstruction are drawn with). Not for the LOD stage,
  /// which draws AtlasSource's output itself.
  tcStageOutput Output(int stage);

  /// Updates `algorithm` (its `port`; a writer, which has no output port, is just updated) with
  /// the retry policy of the class comment; false on an error (GetError) or a cancel
  /// (Cancelled). A cancelled run marks every filter modified: its result is not reused.
  bool Run(vtkAlgorithm* algorithm, int port = 0);

  /// Asks every filter to stop; the running update returns cancelled.
  void Abort();

  /// The last run was cancelled (its error is then "Cancelled").
  bool Cancelled() const { return this->WasCancelled; }

  /// The last run's error ("" if it succeeded): a filter's message without VTK's prefix.
  const std::string& GetError() const { return this->Error; }

  /// What the pipeline did on its own for the open file (the sliver retry); "" if nothing.
  const std::string& GetNote() const { return this->Note; }

  /// Called on every filter's progress event with its class name and its progress (0 to 1).
  void SetProgressCallback(std::function<void(const char* filter, double progress)> callback);

  /// The atlas writer, connected to AtlasSource and named `path` (UTF-8), marked modified so that
  /// a Run writes even when nothing upstream changed. It is one more filter of the pipeline: its
  /// Run builds what the atlas needs with progress and cancel, and reports its errors like any
  /// stage's.
  vtkAlgorithm* AtlasWriterFor(const std::string& path);

  /// The last Run of AtlasWriterFor wrote its file.
  bool AtlasWritten() const;

  /// The glTF writer (tcGLTFWriter at its defaults: the LOD chain by error, MSFT_lod), like
  /// AtlasWriterFor; GltfWritten says whether its last Run wrote the file.
  vtkAlgorithm* GltfWriterFor(const std::string& path);
  bool GltfWritten() const;

  /// The mesh writer (tcMeshWriter: the format by the extension) of `mesh` to `path`, like
  /// AtlasWriterFor; MeshWritten says whether its last Run wrote the file.
  vtkAlgorithm* MeshWriterFor(vtkPolyData* mesh, const std::string& path);
  bool MeshWritten() const;

  ///@{
  /// The filters whose parameters a face sets and whose reports it shows.
  tcMeshReader* GetReader() const { return this->Reader; }
  tcMeshPreparation* GetPreparation() const { return this->Preparation; }
  tcCurvature* GetCurvature() const { return this->Curvature; }
  tcSpectralClustering* GetClustering() const { return this->Clustering; }
  tcFeatureRefinement* GetRefinement() const { return this->Refinement; }
  tcBaseComplex* GetBaseComplex() const { return this->BaseComplex; }
  tcGeometryImages* GetGeometryImages() const { return this->GeometryImages; }
  tcGeometryImageMesh* GetReconstruction() const { return this->Reconstruction; }
  tcSurfaceDistance* GetDistance() const { return this->Distance; }
  ///@}

private:
  std::vector<vtkAlgorithm*> Filters() const;
  /// Updates `algorithm` once and says whether it succeeded, leaving the message in Error.
  bool Execute(vtkAlgorithm* algorithm, int port);
  /// The retry of the class comment, after a run that failed as untraceable.
  bool RunWithoutSlivers(vtkAlgorithm* algorithm, int port);
  void OnProgress(vtkObject* caller, unsigned long, void*);
  void OnError(vtkObject* caller, unsigned long, void* callData);

  vtkNew<tcMeshReader> Reader;
  vtkNew<tcMeshPreparation> Preparation;
  vtkNew<tcCurvature> Curvature;
  vtkNew<tcSpectralClustering> Clustering;
  vtkNew<tcFeatureRefinement> Refinement;
  vtkNew<tcBaseComplex> BaseComplex;
  vtkNew<vtkExtractEdges> BaseEdges;
  vtkNew<tcPathTracing> PathTracing;
  vtkNew<tcGeometryImages> GeometryImages;
  vtkNew<tcAtlasReader> AtlasReader;
  vtkNew<tcGeometryImageMesh> AtlasMesh; ///< every chart at its finest level, for the atlas stage
  vtkNew<tcGeometryImageMesh> Reconstruction;
  vtkNew<vtkLinearSubdivisionFilter> Subdivision; ///< the reconstruction, each triangle in 16
  vtkNew<tcSurfaceDistance> Distance;
  vtkNew<vtkExtractEdges> RebuiltEdges;
  vtkNew<tcAtlasWriter> Writer;
  vtkNew<tcGLTFWriter> GltfWriter;
  vtkNew<tcMeshWriter> MeshWriter;

  std::function<void(const char*, double)> Progress;
  std::string Error;
  /// The filter whose ErrorEvent set Error (nullptr: none, or not a filter's).
  vtkObject* ErrorSource = nullptr;
  std::string Note;
  bool WasCancelled = false;
  bool AtlasFile = false;
};

#endif
