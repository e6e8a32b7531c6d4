// The one unit of a layer linked from another build tree (cmake/TelearTargets.cmake,
// TELEAR_PREBUILT_LAYERS): its code is that tree's archive.
namespace telear {}
