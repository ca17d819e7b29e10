#include "FileKind.h"
#include "MeshFormats.h"

#include <gtest/gtest.h>

using namespace bender;

TEST(FileKind, ClassifiesEveryKindByItsName)
{
  for (const char* mesh : { "a.stl", "A.STL", "dir/b.obj", "c.ply", "d.vtp", "e.vtk", "f.off" })
    EXPECT_EQ(ClassifyFile(mesh), FileKind::Mesh) << mesh;
  for (const char* volume :
    { "a.nrrd", "a.nhdr", "a.nii", "a.NII.GZ", "a.mha", "a.mhd", "/x/y/a.vti" })
    EXPECT_EQ(ClassifyFile(volume), FileKind::Volume) << volume;
  EXPECT_EQ(ClassifyFile("plan.bender.json"), FileKind::Plan);
  EXPECT_EQ(ClassifyFile("other.json"), FileKind::Plan);
  EXPECT_EQ(ClassifyFile("/tmp/autosave.bender-session.json"), FileKind::Session);
  EXPECT_EQ(ClassifyFile("/tmp/AUTOSAVE.Bender-Session.JSON"), FileKind::Session);
}

TEST(FileKind, FoldersAreVolumesAndOtherNamesUnknown)
{
  EXPECT_EQ(ClassifyFile("/data/dicom-series", true), FileKind::Volume);
  // Whatever its name says: a folder is read as a DICOM series.
  EXPECT_EQ(ClassifyFile("/data/scan.stl", true), FileKind::Volume);
  for (const char* unknown :
    { "notes.xyz", "a.gz", "stl", ".stl", "", "dir.stl/readme", "a.vtk.bak" })
    EXPECT_EQ(ClassifyFile(unknown), FileKind::Unknown) << unknown;
  EXPECT_STREQ(FileKindName(FileKind::Unknown), "unknown");
  EXPECT_STREQ(FileKindName(ClassifyFile("x.off")), "mesh");
}

TEST(FileKind, TheRefusalNamesTheFile)
{
  const std::string message = UnknownFileTypeMessage("notes.xyz");
  EXPECT_EQ(message.rfind("notes.xyz: unknown file type", 0), 0u);
  EXPECT_EQ(message.find('\n'), std::string::npos);
}

TEST(FileKind, ARegisteredMeshFormatIsOpenedAsAMesh)
{
  MeshFormat dummy = *FindMeshFormatByName("off");
  dummy.name = "dummy";
  dummy.extensions = { ".dmy" };
  dummy.label = "Dummy mesh";
  {
    ScopedMeshFormat scoped(dummy);
    EXPECT_EQ(ClassifyFile("dir/a.DMY"), FileKind::Mesh);
    EXPECT_NE(UnknownFileTypeMessage("notes.xyz").find(" dmy"), std::string::npos);
  }
  EXPECT_EQ(ClassifyFile("dir/a.DMY"), FileKind::Unknown);
  EXPECT_EQ(UnknownFileTypeMessage("notes.xyz").find(" dmy"), std::string::npos);
  // Every readable row of the table is a mesh to open, and the refusal names it.
  for (const MeshFormat& format : MeshFormats())
  {
    for (const std::string& ext : format.extensions)
    {
      EXPECT_EQ(ClassifyFile("a" + ext) == FileKind::Mesh, format.CanRead()) << ext;
      EXPECT_EQ(UnknownFileTypeMessage("x").find(" " + ext.substr(1)) != std::string::npos,
        format.CanRead())
        << ext;
    }
  }
}
