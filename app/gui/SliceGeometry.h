#ifndef SliceGeometry_h
#define SliceGeometry_h

#include <vtkSmartPointer.h>

class vtkDataArray;
class vtkImageData;
class vtkMatrix4x4;

/// The geometry the slice views and the 3D view's cursor share: the views' colours and axes,
/// a volume's placement in LPS mm (its index-to-LPS matrix, its box) and the patient letters.

/// Each slice view's colour (its title, its trace in the other views, its plane in the 3D view):
/// axial red, coronal green, sagittal yellow (SliceViews::Orientation's order).
extern const unsigned char SliceColours[3][3];
/// The views' names: "Axial", "Coronal", "Sagittal".
extern const char* const SliceNames[3];
/// The LPS axis along each view's normal: axial z (S), coronal y (P), sagittal x (L).
int SliceAxis(int view);

/// The patient direction a vector points to most (LPS: +x left "L", +y posterior "P",
/// +z superior "S"; "R", "A", "I" the other way).
const char* PatientLetter(const double v[3]);

/// The volume's grid without its placement (origin 0, identity direction), sharing the scalars:
/// the placement goes into the slice's matrix, which every image mapper honours.
vtkSmartPointer<vtkImageData> Unplaced(vtkImageData* image);
/// Index-space mm (spacing applied) to LPS: origin + direction * x.
vtkSmartPointer<vtkMatrix4x4> Placement(vtkImageData* image);
/// The box of the voxels' outer faces in LPS (xmin, xmax, ymin, ymax, zmin, zmax): the 8
/// corners through the placement.
void VoxelBox(vtkImageData* image, double bounds[6]);
/// The 0.5 and 99.5 percentiles of the scalars (on a sample of at most ~1M values); the full
/// range when those are equal or the array holds fewer than two finite values.
void RobustRange(vtkDataArray* scalars, double range[2]);
/// The voxel nearest `point` (LPS), false outside the image's extent (or without an image).
bool NearestVoxel(vtkImageData* image, const double point[3], int ijk[3]);

#endif
