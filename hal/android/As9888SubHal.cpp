// SPDX-License-Identifier: GPL-2.0
//
// The AS9888 as a sub-HAL of AOSP's sensors multihal (ISensorsSubHal 2.1,
// hardware/interfaces/sensors/common/default/2.X/multihal/include/V2_1/
// SubHal.h), loaded by android.hardware.sensors@2.1-service.multihal
// through /vendor/etc/sensors/hals.conf. NOT BUILT HERE (no Android tree):
// docs/DECISIONS.md says what was checked against AOSP's headers.
//
// Everything but the translation of types lives in the portable core
// (hal/include/as9888_hal.h), which the project tests on Linux. The core's
// handles are 1..3 (the multihal keeps the upper byte for itself), its
// sensor types and SensorStatus values are Android's.

#include <android-base/logging.h>
#include <hidl/HidlSupport.h>
#include <V2_1/SubHal.h>

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <mutex>
#include <string>
#include <vector>

#include "as9888_hal.h"

namespace {

using ::android::sp;
using ::android::hardware::hidl_handle;
using ::android::hardware::hidl_string;
using ::android::hardware::hidl_vec;
using ::android::hardware::Return;
using ::android::hardware::Void;
using ::android::hardware::sensors::V1_0::MetaDataEventType;
using ::android::hardware::sensors::V1_0::OperationMode;
using ::android::hardware::sensors::V1_0::RateLevel;
using ::android::hardware::sensors::V1_0::Result;
using ::android::hardware::sensors::V1_0::SensorFlagBits;
using ::android::hardware::sensors::V1_0::SensorStatus;
using ::android::hardware::sensors::V1_0::SharedMemInfo;
using ::android::hardware::sensors::V2_1::Event;
using ::android::hardware::sensors::V2_1::SensorInfo;
using ::android::hardware::sensors::V2_1::SensorType;
using ::android::hardware::sensors::V2_1::implementation::IHalProxyCallback;
using ::android::hardware::sensors::V2_1::implementation::ISensorsSubHal;

// Optional: "key value" lines for a board with two chips, another trigger
// or other paths (as9888_hal_config_parse())
constexpr char kConfigPath[] = "/vendor/etc/sensors/as9888-hal.conf";

Result toResult(int ret) {
    switch (ret) {
        case 0:
            return Result::OK;
        case -EINVAL:
            return Result::BAD_VALUE;
        case -EACCES:
        case -EPERM:
            return Result::PERMISSION_DENIED;
        default:
            return Result::INVALID_OPERATION;
    }
}

class As9888SubHal : public ISensorsSubHal {
  public:
    Return<void> getSensorsList_2_1(getSensorsList_2_1_cb cb) override {
        std::vector<SensorInfo> list;
        std::lock_guard<std::mutex> lock(mLock);

        if (open()) {
            const as9888_sensor_info* info;
            size_t n = as9888_hal_sensors(mHal, &info);

            for (size_t i = 0; i < n; i++) {
                SensorInfo s;

                s.sensorHandle = info[i].handle;
                s.name = info[i].name;
                s.vendor = info[i].vendor;
                s.version = 1;
                s.type = static_cast<SensorType>(info[i].type);
                s.typeAsString = info[i].type_name;
                s.maxRange = info[i].max_range;
                s.resolution = info[i].resolution;
                s.power = info[i].power_ma;
                s.minDelay = info[i].min_delay_us;
                s.fifoReservedEventCount = 0;
                s.fifoMaxEventCount = info[i].fifo_max;
                s.requiredPermission = "";
                s.maxDelay = info[i].max_delay_us;
                // continuous, not a wake-up sensor (reporting mode 0)
                s.flags = 0;
                list.push_back(s);
            }
        }
        cb(list);
        return Void();
    }

    Return<Result> setOperationMode(OperationMode mode) override {
        // no data injection: the sensors are the chip's
        return mode == OperationMode::NORMAL ? Result::OK : Result::BAD_VALUE;
    }

    Return<Result> activate(int32_t handle, bool enabled) override {
        // held across the call: initialize() must not close the core under it
        std::lock_guard<std::mutex> lock(mLock);
        as9888_hal* h = mHal;

        return h ? call(h, as9888_hal_activate(h, handle, enabled), "activate", handle)
                 : Result::INVALID_OPERATION;
    }

    Return<Result> batch(int32_t handle, int64_t periodNs, int64_t latencyNs) override {
        // held across the call: initialize() must not close the core under it
        std::lock_guard<std::mutex> lock(mLock);
        as9888_hal* h = mHal;

        return h ? call(h, as9888_hal_batch(h, handle, periodNs, latencyNs), "batch", handle)
                 : Result::INVALID_OPERATION;
    }

    Return<Result> flush(int32_t handle) override {
        // held across the call: initialize() must not close the core under it
        std::lock_guard<std::mutex> lock(mLock);
        as9888_hal* h = mHal;

        return h ? call(h, as9888_hal_flush(h, handle), "flush", handle)
                 : Result::INVALID_OPERATION;
    }

    Return<Result> injectSensorData_2_1(const Event& /* event */) override {
        return Result::INVALID_OPERATION;
    }

    Return<void> registerDirectChannel(const SharedMemInfo& /* mem */,
                                       registerDirectChannel_cb cb) override {
        cb(Result::INVALID_OPERATION, -1);
        return Void();
    }

    Return<Result> unregisterDirectChannel(int32_t /* channelHandle */) override {
        return Result::INVALID_OPERATION;
    }

    Return<void> configDirectReport(int32_t /* sensorHandle */, int32_t /* channelHandle */,
                                    RateLevel /* rate */, configDirectReport_cb cb) override {
        cb(Result::INVALID_OPERATION, 0);
        return Void();
    }

    Return<void> debug(const hidl_handle& fd, const hidl_vec<hidl_string>& /* args */) override {
        std::lock_guard<std::mutex> lock(mLock);
        as9888_hal* h = mHal;
        char err[256] = "";

        if (fd.getNativeHandle() == nullptr || fd->numFds < 1) return Void();
        if (h) as9888_hal_error(h, err, sizeof(err));
        dprintf(fd->data[0], "as9888: %s; last error: %s\n", h ? "open" : "no AS9888 found",
                err[0] ? err : "none");
        return Void();
    }

    const std::string getName() override { return "AS9888"; }

    Return<Result> initialize(const sp<IHalProxyCallback>& callback) override {
        std::lock_guard<std::mutex> lock(mLock);

        // the framework restarted: every sensor starts off again
        as9888_hal_close(mHal);
        mHal = nullptr;
        mCallback = callback;
        return open() ? Result::OK : Result::NO_MEMORY;
    }

  private:
    // the core calls this from its reader thread
    static void post(void* ctx, const as9888_event* ev, size_t n) {
        auto* self = static_cast<As9888SubHal*>(ctx);
        std::vector<Event> events(n);

        for (size_t i = 0; i < n; i++) {
            Event& e = events[i];

            e.timestamp = ev[i].timestamp_ns;
            e.sensorHandle = ev[i].handle;
            e.sensorType = static_cast<SensorType>(ev[i].type);
            if (ev[i].type == AS9888_TYPE_META_DATA) {
                e.u.meta.what = MetaDataEventType::META_DATA_FLUSH_COMPLETE;
            } else if (ev[i].type == AS9888_TYPE_MAGNETIC_FIELD_UNCALIBRATED) {
                e.u.uncal.x = ev[i].v[0];
                e.u.uncal.y = ev[i].v[1];
                e.u.uncal.z = ev[i].v[2];
                e.u.uncal.x_bias = ev[i].v[3];
                e.u.uncal.y_bias = ev[i].v[4];
                e.u.uncal.z_bias = ev[i].v[5];
            } else {
                e.u.vec3.x = ev[i].v[0];
                e.u.vec3.y = ev[i].v[1];
                e.u.vec3.z = ev[i].v[2];
                e.u.vec3.status = static_cast<SensorStatus>(ev[i].status);
            }
        }
        // no wake-up sensors: an unlocked wake lock
        self->mCallback->postEvents(events, self->mCallback->createScopedWakelock(false));
    }

    // with mLock held
    bool open() {
        as9888_hal_config cfg;
        char err[512];

        if (mHal) return true;
        as9888_hal_config_defaults(&cfg);
        if (access(kConfigPath, F_OK) == 0 &&
            as9888_hal_config_load(kConfigPath, &cfg, err, sizeof(err))) {
            LOG(ERROR) << "as9888: " << err;
            return false;
        }
        if (as9888_hal_open(&cfg, post, this, &mHal, err, sizeof(err))) {
            LOG(ERROR) << "as9888: " << err;
            mHal = nullptr;
            return false;
        }
        return true;
    }

    static Result call(as9888_hal* h, int ret, const char* what, int32_t handle) {
        if (ret && ret != -EINVAL) {
            char err[256];

            as9888_hal_error(h, err, sizeof(err));
            LOG(ERROR) << "as9888: " << what << " of sensor " << handle << ": " << err;
        }
        return toResult(ret);
    }

    // guards mHal and mCallback: every call into the core holds it, so
    // initialize() never closes the core while another call uses it (the
    // core's reader thread, which calls post(), never takes it)
    std::mutex mLock;
    as9888_hal* mHal = nullptr;
    sp<IHalProxyCallback> mCallback;
};

}  // namespace

ISensorsSubHal* sensorsHalGetSubHal_2_1(uint32_t* version) {
    static As9888SubHal subHal;

    *version = SUB_HAL_2_1_VERSION;
    return &subHal;
}
