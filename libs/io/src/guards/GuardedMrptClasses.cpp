// Two stock deserializers crash on a damaged file, inside MRPT, where no exception handler
// can help:
// - CActionCollection stores each action read into a deep-copying pointer, which clones it:
//   an action stored as "nullptr" is dereferenced.
// - CActionRobotMovement2D::serializeFrom, versions 0 and 1, reads the pose PDF object
// and then calls poseChange->getMean() on it. A damaged file that stores "nullptr" (or an
// object of another class) there makes MRPT dereference a null pointer: a segfault no
// exception handler can catch. Newer versions store the same PDF for non-odometry estimates
// and leave the null for whoever reads the action next.
//
// The guards: subclasses that read the risky part themselves and refuse what MRPT would
// dereference with an exception. The collection reads its count and actions (one at a time,
// nothing allocated from the count) and inserts each, which clones it. The movement reads its
// PDF itself, refuses a missing one with an exception,
// and hands MRPT's own reader the same bytes from a memory stream, so the format is still
// MRPT's. It is registered in MRPT's class registry under the stock class's name, which is
// how CArchive::ReadObject finds what to create. Each reports the stock class as its runtime
// class, so IS_CLASS, class names and re-serialization see a CActionRobotMovement2D, and
// clone() gives a plain one.
#include "GuardedMrptClasses.h"

#include <mrpt/io/CMemoryStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/poses/CPosePDF.h>
#include <mrpt/rtti/CObject.h>
#include <mrpt/serialization/CArchive.h>

#include <array>
#include <iostream>
#include <mutex>
#include <sstream>
#include <stdexcept>

namespace lodestone::io::detail {
namespace {

using mrpt::obs::CActionRobotMovement2D;

class GuardedRobotMovement2D : public CActionRobotMovement2D {
  public:
    const mrpt::rtti::TRuntimeClassId* GetRuntimeClass() const override {
        return &CActionRobotMovement2D::GetRuntimeClassIdStatic();
    }

  protected:
    void serializeFrom(mrpt::serialization::CArchive& in, uint8_t version) override {
        if (version > 1) {
            CActionRobotMovement2D::serializeFrom(in, version);
            if (!poseChange) throw std::runtime_error("CActionRobotMovement2D: no pose PDF stored");
            return;
        }
        auto pdf = in.ReadObject<mrpt::poses::CPosePDF>();
        if (!pdf) {
            throw std::runtime_error(
                "CActionRobotMovement2D (version " + std::to_string(version) +
                "): the pose PDF is missing or not a CPosePDF");
        }
        // What follows the PDF: int32 method; version 1 adds bool, 2 floats, bool, 2 int32.
        std::array<std::uint8_t, 22> tail{};
        const std::size_t tailBytes = version == 0 ? 4 : 22;
        if (in.ReadBuffer(tail.data(), tailBytes) != tailBytes) {
            throw std::runtime_error("CActionRobotMovement2D: the file ends inside the action");
        }
        mrpt::io::CMemoryStream buffer;
        auto out = mrpt::serialization::archiveFrom(buffer);
        out << *pdf;
        out.WriteBuffer(tail.data(), tailBytes);
        buffer.Seek(0);
        auto again = mrpt::serialization::archiveFrom(buffer);
        CActionRobotMovement2D::serializeFrom(again, version);
    }
};

class GuardedActionCollection : public mrpt::obs::CActionCollection {
  public:
    const mrpt::rtti::TRuntimeClassId* GetRuntimeClass() const override {
        return &CActionCollection::GetRuntimeClassIdStatic();
    }

  protected:
    void serializeFrom(mrpt::serialization::CArchive& in, uint8_t version) override {
        if (version != 0) {
            CActionCollection::serializeFrom(in, version);  // MRPT's verdict on the version
            return;
        }
        std::uint32_t count = 0;
        in >> count;
        clear();
        for (std::uint32_t k = 0; k < count; ++k) {
            const auto action = in.ReadObject<mrpt::obs::CAction>();
            if (!action) {
                throw std::runtime_error("CActionCollection: action " + std::to_string(k) +
                                         " is null or not a CAction");
            }
            insert(*action);  // a copy of the stock class (clone), as MRPT stores it
        }
    }
};

const mrpt::rtti::TRuntimeClassId* actionBaseClass() {
    return &mrpt::obs::CAction::GetRuntimeClassIdStatic();
}
const mrpt::rtti::TRuntimeClassId* serializableBaseClass() {
    return &mrpt::serialization::CSerializable::GetRuntimeClassIdStatic();
}

const mrpt::rtti::TRuntimeClassId kGuardedRobotMovement2D{
    CActionRobotMovement2D::className,
    [] { return std::shared_ptr<mrpt::rtti::CObject>(std::make_shared<GuardedRobotMovement2D>()); },
    &actionBaseClass};

const mrpt::rtti::TRuntimeClassId kGuardedActionCollection{
    mrpt::obs::CActionCollection::className,
    [] { return std::shared_ptr<mrpt::rtti::CObject>(std::make_shared<GuardedActionCollection>()); },
    &serializableBaseClass};

}  // namespace

void installGuardedMrptClasses() {
    static std::once_flag once;
    std::call_once(once, [] {
        // MRPT registers its classes lazily; ours must come after the stock ones.
        mrpt::rtti::registerAllPendingClasses();
        // The registry warns on std::cerr that a name is overwritten: that is the point here.
        std::ostringstream quiet;
        auto* previous = std::cerr.rdbuf(quiet.rdbuf());
        mrpt::rtti::registerClass(&kGuardedRobotMovement2D);
        mrpt::rtti::registerClass(&kGuardedActionCollection);
        std::cerr.rdbuf(previous);
    });
}

}  // namespace lodestone::io::detail
