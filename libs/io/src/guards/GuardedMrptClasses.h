#pragma once

namespace lodestone::io::detail {

/** Registers every stock class a rawlog may hold (mrpt-maps' observations too), then puts
 * checking readers in MRPT's class registry in place of stock classes whose deserializers
 * trust what they read (see GuardedMrptClasses.cpp), and makes cv::Mat allocations charge the
 * reading budget (BudgetedMatAllocator.h). Idempotent and thread-safe; RawlogReader calls it
 * before its first read. */
void installGuardedMrptClasses();

}  // namespace lodestone::io::detail
