// SPDX-License-Identifier: GPL-2.0
/*
 * The factory test's device when the AS9888 IIO driver owns the chip: its
 * interfaces (Documentation/ABI/testing/sysfs-bus-iio-as9888) stand in for
 * register access. The driver registers two IIO devices per chip: the test
 * runs on the accelerometer's (as9888-accel, iio:deviceN) and reaches the
 * magnetometer's (as9888-magn, iio:deviceM, its sibling below the bus
 * device) for step 2 only.
 *
 *   step 1  the device ID (WIA) is read through debugfs (the driver binds
 *           to an unknown one too, saying so); the driver loaded the
 *           trims when it bound; the EEPROM comes from its NVMEM
 *           provider and the DAC values go through
 *           in_accel_*_calibbias (the calibbias whose DAC they are),
 *           read back (D10)
 *   step 2  the magnetometer device's selftest attribute runs the test
 *           and reads back its verdict (pass/fail); the adjusted readings
 *           come from debugfs iio/iio:deviceM/selftest_readings and are
 *           judged again here against the windows of steps 2-17..2-22.
 *           Without them (debugfs not mounted or not readable) those
 *           judgments are skipped, saying so, and the driver's verdict
 *           decides. Without the magnetometer device the step fails
 *           (2-4.magn), naming the directory it is missing from
 *   step 3  samples from the accelerometer device's buffer on the
 *           driver's data-ready trigger (INT1, "as9888-dev<N>"):
 *           accelerometer X, Y, Z, the temperature code and the
 *           timestamp; the driver checks ST1 and EMPT of every sample and
 *           delivers none that fails, and the DAC goes through calibbias.
 *           The filter is in_accel_oversampling_ratio: 1 off, 4 on (ALPF).
 *           The capture runs from the first level run to the end of the
 *           test. The driver takes a calibbias write while it runs, in the
 *           gap between two samples, after the sample before it went into
 *           the buffer (Documentation/iio/as9888.rst): the samples the
 *           buffer holds when the write returns were measured with the old
 *           DAC and are dropped, every later one with the new
 *
 * The driver delivers compensated accelerometer samples (1024 per g); the
 * application note judges and averages the chip's own output. The test
 * takes it back (accel_raw.h): with the EEPROM, the driver's calibbias as
 * read and the DAC it gives, Ot and St at each sample's own TMPS, then
 * as9888_accel_uncompensate(), checked by compensating again. An axis at
 * the limit of the driver's output (the driver's mark of a saturated
 * chip) comes back as the chip's rail, which the saturation judgment of
 * steps 3-14..3-19 fails as on the register backend.
 *
 * Of the pin checks of D11, INT1 is judged by the data-ready trigger
 * delivering samples; RSTN and INT2 need the pins, which the driver owns or
 * does not use: they are reported as skipped (run --backend raw with the
 * driver unbound for them). Every attribute the test changes is saved
 * first and put back by finish(), in the order saved, so the device is
 * left as it was found; a command that wants the new calibration applied
 * writes it afterwards (iio_apply_record()).
 */
#include <errno.h>
#include <fcntl.h>
#include <dirent.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "chip/accel_raw.h"
#include "ftest/ftest_internal.h"
#include "chip/iio_cal.h"
#include "chip/iio_busy.h"
#include "iio_scan.h"
#include "chip/iio_value.h"

/*
 * The data-ready rate during the test is the fastest the driver offers
 * for the accelerometer alone (sampling_frequency_available, read after
 * the filter is set: 400 Hz without it, 125 Hz with it): the driver
 * offers only rates whose period holds the measurement, t_PD and the
 * bus transfers. Rates above this are not taken as a driver's.
 */
#define IIO_TEST_RATE_MAX_HZ	100000
/* Buffer length during the test, in samples, and as buffer/length takes it */
#define IIO_TEST_BUFFER_SAMPLES	256
#define IIO_TEXT_(n)		#n
#define IIO_TEXT(n)		IIO_TEXT_(n)
#define IIO_TEST_BUFFER_LEN	IIO_TEXT(IIO_TEST_BUFFER_SAMPLES)
/* Samples taken from the buffer in one read (at least: the largest size) */
#define IIO_READ_SAMPLES	32
/*
 * Reads that drop what the capture holds: at least twice the buffer's
 * length. A capture that still has samples after them is delivering
 * faster than any rate the driver offers
 */
#define IIO_DRAIN_READS_MAX	(2 * IIO_TEST_BUFFER_SAMPLES / IIO_READ_SAMPLES)
/* The largest sample of the test's channels, in bytes */
#define IIO_SAMPLE_MAX		32
/*
 * The longest wait for the next sample: longer means the capture stalled.
 * A busy system only slows a run down; it does not fail it
 */
#define IIO_SAMPLE_STALL_MS	2000
/*
 * How often a level run starts again after another program turned the
 * buffer off under it (libiio's local backend does so as a client starts,
 * before it finds the device taken)
 */
#define IIO_RETAKE_MAX		2
#define IIO_SAVED_MAX		32
#define IIO_NAME_MAX		64
#define IIO_SCAN_CHANNELS	4
#define IIO_SCAN_TEMP		3
#define IIO_OVERSAMPLING_ATTR	"in_accel_oversampling_ratio"
#define IIO_OVERSAMPLING_OFF	"1"
#define IIO_OVERSAMPLING_ALPF	"4"
#define IIO_SELFTEST_READINGS	"selftest_readings"
#define IIO_REG_ACCESS		"direct_reg_access"
#define IIO_TRIGGER_ATTR	"trigger/current_trigger"

/* The buffer's channels the test uses, in the order of this table */
static const char *const scan_channel[IIO_SCAN_CHANNELS] = {
	[0] = "in_accel_x", [1] = "in_accel_y", [2] = "in_accel_z",
	[IIO_SCAN_TEMP] = "in_temp",
};

/*
 * An attribute as found: @changed once the test wrote another value to
 * it, which finish() then puts back; @set once change_attr() wrote it or
 * found it as wanted. @file is kept open from the first read to the end of
 * the test: the test reads and writes these again and again (iio_attr.h)
 */
struct saved_attr {
	char name[IIO_NAME_MAX];
	char value[IIO_ATTR_MAX];
	bool changed;
	bool set;
	struct iio_attr file;
};

/**
 * struct iio_test_dev - the driver-backed test device
 * @dir:	the accelerometer IIO device's sysfs directory
 * @dfd:	that directory, open (iio_dir_open())
 * @magn:	the magnetometer IIO device's, once step 2 found it
 * @scan_dir:	its scan_elements directory, relative to @dir
 * @chardev:	its character device
 * @trigger:	the name of its data-ready trigger
 * @layout:	where each of scan_channel[] sits in a sample
 * @sample_bytes: size of one buffer sample; 0 until @layout is read (at
 *		the first buffer set-up)
 * @saved:	attributes to put back at the end, in this order
 * @n_saved:	how many
 * @calibbias:	in_accel_{x,y,z}_calibbias, open (their @saved entries')
 * @enable:	buffer/enable, open from step 1-4 on
 * @capture_fd:	the character device while the test's capture runs, else -1
 * @int1_seen:	D11's INT1 check is made (at the first level run)
 * @comp:	what the driver compensates the samples with: the EEPROM
 *		and the calibration the last DAC write read back
 */
struct iio_test_dev {
	char dir[IIO_PATH_MAX];
	int dfd;
	char magn[IIO_PATH_MAX];
	const char *scan_dir;
	char chardev[IIO_PATH_MAX];
	char trigger[IIO_NAME_MAX];
	struct iio_scan_channel layout[IIO_SCAN_CHANNELS];
	unsigned int sample_bytes;
	struct saved_attr saved[IIO_SAVED_MAX];
	unsigned int n_saved;
	struct iio_attr calibbias[AS9888_AXES];
	struct iio_attr enable;
	int capture_fd;
	bool int1_seen;
	struct accel_comp comp;
};

/*
 * Remember @name's value, once; *@a receives its entry. 0, or -errno.
 */
static int save_attr(struct iio_test_dev *d, const char *name,
		     struct saved_attr **a)
{
	struct saved_attr *s;
	unsigned int i;
	int ret;

	for (i = 0; i < d->n_saved; i++)
		if (!strcmp(d->saved[i].name, name)) {
			*a = &d->saved[i];
			return 0;
		}
	if (d->n_saved == IIO_SAVED_MAX)
		return -ENOSPC;
	s = &d->saved[d->n_saved];
	if (snprintf(s->name, sizeof(s->name), "%s", name) >= (int)sizeof(s->name))
		return -ENAMETOOLONG;
	ret = iio_attr_open(&s->file, d->dfd, name, true);
	if (ret)
		return ret;
	ret = iio_attr_read(&s->file, s->value, sizeof(s->value));
	if (ret < 0) {
		iio_attr_close(&s->file);
		return ret;
	}
	s->changed = false;
	s->set = false;
	d->n_saved++;
	*a = s;

	return 0;
}

/*
 * Save, then write @value to @name. An attribute that reads @value as it
 * was saved is left alone (and not put back) the first time: each write to
 * the driver's attributes costs a system call and, for the buffer's, the
 * IIO core's locks. After that it is always written: another program may
 * have changed it since (a level run taken again sets the buffer up again).
 */
static int change_attr(struct iio_test_dev *d, const char *name,
		       const char *value)
{
	struct saved_attr *a;
	bool first;
	int ret = save_attr(d, name, &a);

	if (ret < 0)
		return ret;
	first = !a->set;
	a->set = true;
	if (first && !strcmp(a->value, value))
		return 0;
	a->changed = true;

	return iio_attr_write(&a->file, value);
}

static uint64_t iio_now_ns(struct ftest_ctx *x)
{
	struct timespec ts;

	(void)x;
	clock_gettime(CLOCK_MONOTONIC, &ts);

	return (uint64_t)ts.tv_sec * 1000000000ULL + (uint64_t)ts.tv_nsec;
}

static void iio_sleep_ns(struct ftest_ctx *x, uint64_t ns)
{
	struct timespec ts = {
		.tv_sec = (time_t)(ns / 1000000000ULL),
		.tv_nsec = (long)(ns % 1000000000ULL),
	};

	(void)x;
	while (nanosleep(&ts, &ts) && errno == EINTR)
		;
}

/* A driver interface failed: @why says which and how; the test stops */
static int iio_failed(struct ftest_ctx *x, const char *step, const char *what,
		      const char *why, int err)
{
	report_add(&x->res->report, step, what, JUDGMENT_FAIL, NULL, "%s", why);
	x->stop = true;

	return err;
}

/*
 * Write the DAC values through calibbias (saved by ftest_run_iio()) and
 * read them back into x->dac; the calibration read back is what the
 * driver compensates the next samples with
 */
static int put_dac(struct ftest_ctx *x, const uint8_t dac[AS9888_AXES],
		   const char *step, bool *same)
{
	struct iio_test_dev *d = x->dev;
	uint8_t got[AS9888_AXES];
	char err[IIO_ERR_LEN];
	int ret;

	ret = iio_write_dac(d->dir, d->calibbias, &x->res->ee, dac, got,
			    &d->comp.cal, err, sizeof(err));
	if (ret)
		return iio_failed(x, step, "DAC through calibbias", err, ret);
	memcpy(x->dac, got, AS9888_AXES);
	*same = !memcmp(got, dac, AS9888_AXES);

	return 0;
}

/*
 * The driver's data-ready trigger, named as9888-dev<N> after the
 * accelerometer device iio:device<N>, into d->trigger: 0, or -ENOENT when
 * there is none. @current: the device's current_trigger as found.
 */
static int find_trigger(struct iio_test_dev *d, const char *current)
{
	const char *base = strrchr(d->dir, '/');
	char want[IIO_NAME_MAX];
	int ret;

	snprintf(want, sizeof(want), "%s-dev%s", IIO_CHIP_NAME,
		 base + 1 + strlen(IIO_DEVICE_PREFIX));
	/*
	 * The device's trigger is that one already (the driver sets it when
	 * it binds): current_trigger names only a registered trigger, and the
	 * IIO core registers no two of one name. No need to look through the
	 * bus then.
	 */
	if (!strcmp(current, want)) {
		snprintf(d->trigger, sizeof(d->trigger), "%s", want);
		return 0;
	}

	ret = iio_find_trigger(iio_sysfs_root(), want);
	if (!ret)
		snprintf(d->trigger, sizeof(d->trigger), "%s", want);

	return ret;
}

/*
 * Another program holds the buffer or the character device: the test
 * stops, naming the holders and what to do
 */
static int device_taken(struct ftest_ctx *x, const char *step,
			const char *name, const char *limits)
{
	struct iio_test_dev *d = x->dev;
	char who[IIO_ERR_LEN];

	if (iio_chardev_holders("/proc", d->chardev, who, sizeof(who)) <= 0)
		snprintf(who, sizeof(who), "no process this user can see");
	ftest_judge(x, step, name, false, limits,
		    "%s busy for %u s: stop the program holding it, or raise --busy-timeout; holder: %s",
		    d->chardev, x->o->busy_timeout_ms / 1000, who);
	x->stop = true;

	return -EBUSY;
}

/*
 * Register @reg of the chip behind the device at @dir into @val, through the
 * IIO core's debugfs file (its address written, the value read back). @path
 * receives the file's path, for messages. Returns 0, -EINVAL when the answer
 * is not a register value, or -errno.
 */
static int read_reg_debugfs(const char *dir, unsigned int reg,
			    unsigned int *val, char *path, size_t path_size)
{
	const char *base = strrchr(dir, '/');
	char ddir[IIO_PATH_MAX], sel[16], buf[IIO_ATTR_MAX], *end;
	unsigned long v;
	int ret, n;

	if (path_size)
		path[0] = '\0';
	base = base ? base + 1 : dir;
	n = snprintf(ddir, sizeof(ddir), "%s/iio/%s", iio_debugfs_root(), base);
	if (n < 0 || (size_t)n >= sizeof(ddir))
		return -ENAMETOOLONG;
	n = snprintf(path, path_size, "%s/%s", ddir, IIO_REG_ACCESS);
	if (n < 0 || (size_t)n >= path_size)
		return -ENAMETOOLONG;

	snprintf(sel, sizeof(sel), "0x%02x", reg);
	ret = iio_write_attr(ddir, IIO_REG_ACCESS, sel);
	if (ret)
		return ret;
	ret = iio_read_attr(ddir, IIO_REG_ACCESS, buf, sizeof(buf));
	if (ret < 0)
		return ret;
	errno = 0;
	v = strtoul(buf, &end, 0);
	if (end == buf || *end || errno || v > 0xff)
		return -EINVAL;
	*val = v;

	return 0;
}

/*
 * 1-4: the driver binds to an unknown ID too (a compatible part), saying
 * so in the kernel log: the ID is read through debugfs, or skipped saying
 * why (debugfs not mounted or not readable)
 */
static int judge_wia(struct ftest_ctx *x)
{
	struct iio_test_dev *d = x->dev;
	char path[IIO_PATH_MAX], why[IIO_ERR_LEN];
	unsigned int wia;
	int ret;

	ret = read_reg_debugfs(d->dir, AS9888_REG_WIA, &wia, path,
			       sizeof(path));
	if (ret) {
		snprintf(why, sizeof(why),
			 "%s: %s (the driver logs an unknown ID when it binds)",
			 path, strerror(-ret));
		ftest_skip(x, "1-4", "device ID (WIA)", why);
		return 0;
	}
	ftest_judge(x, "1-4", "device ID (WIA)", wia == AS9888_WIA_VAL, "0x48",
		    "0x%02x (%s)", wia, path);
	ftest_value(x, wia, AS9888_WIA_VAL, AS9888_WIA_VAL, "code");

	return wia != AS9888_WIA_VAL && x->stop ? -ENODEV : 0;
}

static int iio_step1(struct ftest_ctx *x)
{
	struct iio_test_dev *d = x->dev;
	const uint8_t *dac;
	uint8_t raw[AS9888_EEPROM_LEN], want[AS9888_AXES];
	bool same;
	int axis, ret;

	ftest_skip(x, "1-2.rstn", "RSTN pin check (D11)",
		   "the driver owns RSTN (--backend raw with the driver unbound checks it)");
	ret = judge_wia(x);
	if (ret || x->stop)
		return ret;

	/*
	 * The test takes the buffer, never from another program: a capture
	 * that is under way gets its turn first, for a bounded time
	 */
	ret = iio_attr_open(&d->enable, d->dfd, "buffer/enable", true);
	if (!ret)
		ret = iio_wait_enable_off(&d->enable, x->o->busy_timeout_ms,
					  IIO_BUSY_POLL_MS);
	if (ret == -EBUSY)
		return device_taken(x, "1-4.free", "device free for the test",
				    "buffer not enabled");
	if (ret < 0)
		return ftest_io_failed(x, "1-4.free", "buffer/enable", ret);
	ftest_judge(x, "1-4.free", "device free for the test", true,
		    "buffer not enabled", "%s", d->dir);

	ret = iio_read_eeprom(d->dir, raw);
	if (ret)
		return ftest_io_failed(x, "1-7", "EEPROM read (NVMEM)", ret);
	ret = ftest_check_eeprom(x, raw);
	if (ret || x->stop)
		return ret;

	/* 1-30..1-39: the DAC values; the driver loaded the other trims */
	for (axis = 0; axis < AS9888_AXES; axis++)
		want[axis] = x->res->ee.axis[axis].da;
	dac = x->o->apply_dac ? x->o->apply_dac : want;
	ret = put_dac(x, dac, "1-39", &same);
	if (ret)
		return ret;
	ftest_judge(x, "1-39", "register R/W check (D10)", same,
		    "calibbias reads back what was written",
		    "DAC 0x%02x 0x%02x 0x%02x", x->dac[0], x->dac[1], x->dac[2]);

	return 0;
}

/* 2-17..2-23 on the adjusted readings of debugfs and the driver's verdict */
static void judge_selftest_readings(struct ftest_ctx *x,
				    const int32_t adj[AS9888_AXES], bool pass)
{
	bool windows = true;
	int axis;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		bool ok = as9888_selftest_window_ok(axis, adj[axis]);

		windows &= ok;
		if (!ftest_judge_selftest_axis(x, axis, ok, adj[axis], "") &&
		    x->stop)
			return;
	}
	/*
	 * The driver also fails the test on a magnetometer overflow in the
	 * normal measurement or HST in either: with the windows met, that
	 * is what its verdict adds.
	 */
	if (windows)
		ftest_judge(x, "2-13", "normal measurement without overflow",
			    pass, "driver's verdict pass",
			    "driver's verdict %s", pass ? "pass" : "fail");
	else
		ftest_judge(x, "2-23.agrees", "driver's verdict agrees", !pass,
			    "fail when a window is missed", "%s",
			    pass ? "pass" : "fail");
}

/* Without the readings, the driver's verdict alone; said, never guessed */
static void judge_selftest_verdict(struct ftest_ctx *x, bool pass,
				   const char *unavailable)
{
	char why[JUDGMENT_TEXT_LEN];
	int axis;

	snprintf(why, sizeof(why),
		 "reading not available (%.100s): judged by the driver",
		 unavailable);
	for (axis = 0; axis < AS9888_AXES; axis++)
		ftest_skip_selftest_axis(x, axis, why);
	ftest_judge(x, "2-23.verdict", "self-test verdict of the driver", pass,
		    "pass (windows of 2-17..2-22, no overflow, HST)",
		    "%s; the adjusted readings were not seen (%s)",
		    pass ? "pass" : "fail", unavailable);
}

/*
 * The magnetometer device of the chip into d->magn: 2-4.magn judges it
 * there; without it the step cannot run (-ENODEV)
 */
static int find_magn(struct ftest_ctx *x)
{
	struct iio_test_dev *d = x->dev;
	char parent[IIO_PATH_MAX], found[IIO_ERR_LEN];
	int ret;

	*parent = '\0';
	ret = iio_find_magn(d->dir, d->magn, sizeof(d->magn), parent,
			    sizeof(parent));
	if (!ret)
		snprintf(found, sizeof(found), "%s", d->magn);
	else if (!*parent)
		snprintf(found, sizeof(found), "cannot resolve %s to its bus device: %s",
			 d->dir, strerror(-ret));
	else
		snprintf(found, sizeof(found),
			 "none in %s: a driver without it, or it failed to register (see the kernel log)",
			 parent);
	ftest_judge(x, "2-4.magn", "magnetometer device", !ret,
		    "the chip's " IIO_MAGN_NAME " IIO device", "%s", found);

	return ret ? -ENODEV : 0;
}

/* Read the adjusted readings and judge them, or the verdict alone */
static void judge_selftest(struct ftest_ctx *x, bool pass)
{
	struct iio_test_dev *d = x->dev;
	int32_t adj[AS9888_AXES];
	char val[IIO_ATTR_MAX], path[IIO_PATH_MAX], why[IIO_ERR_LEN];
	int ret;

	ret = iio_read_debugfs(d->magn, IIO_SELFTEST_READINGS, val, sizeof(val),
			       path, sizeof(path));
	if (ret < 0) {
		snprintf(why, sizeof(why), "%s: %s", path, strerror(-ret));
	} else {
		ret = iio_parse_selftest_readings(val, adj);
		if (ret == -EINVAL &&
		    !ftest_judge(x, "2-15.readings", "self-test readings readable", false,
				 "X Y Z, LSB with three decimals", "%s: \"%s\"",
				 path, val) && x->stop)
			return;
		if (ret)
			snprintf(why, sizeof(why), "%s reads \"%s\"", path, val);
	}
	if (ret)
		judge_selftest_verdict(x, pass, why);
	else
		judge_selftest_readings(x, adj, pass);
}

/* @entry ("in_accel_x_en") is the enable file of one of scan_channel[] */
static bool is_test_channel(const char *entry)
{
	unsigned int i;
	size_t len;

	for (i = 0; i < IIO_SCAN_CHANNELS; i++) {
		len = strlen(scan_channel[i]);
		if (!strncmp(entry, scan_channel[i], len) &&
		    !strcmp(entry + len, "_en"))
			return true;
	}

	return false;
}

/*
 * Only scan_channel[] enabled, the other channels (the timestamp) off;
 * every one saved first. 0, or -errno
 */
static int scan_enable(struct iio_test_dev *d)
{
	char name[IIO_PATH_MAX];
	struct dirent *de;
	DIR *dir;
	int ret;

	ret = openat(d->dfd, d->scan_dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
	dir = ret < 0 ? NULL : fdopendir(ret);
	if (!dir)
		return -errno;
	ret = 0;
	while (!ret && (de = readdir(dir))) {
		size_t len = strlen(de->d_name);

		if (len < 4 || strcmp(de->d_name + len - 3, "_en"))
			continue;
		snprintf(name, sizeof(name), "%s/%s", d->scan_dir, de->d_name);
		ret = change_attr(d, name, is_test_channel(de->d_name) ? "1" : "0");
	}
	closedir(dir);

	return ret;
}

/*
 * The places of scan_channel[] in a sample, from their _index and _type
 * (read once: they are fixed while the device exists). 0, or -errno with
 * the channel it failed on in *@what
 */
static int scan_layout(struct iio_test_dev *d, const char **what)
{
	char name[IIO_PATH_MAX], val[IIO_ATTR_MAX];
	unsigned int i;
	int ret;

	for (i = 0; i < IIO_SCAN_CHANNELS; i++) {
		struct iio_scan_channel *l = &d->layout[i];

		*what = scan_channel[i];
		snprintf(name, sizeof(name), "%s/%s_index", d->scan_dir,
			 scan_channel[i]);
		if (iio_read_attr_at(d->dfd, name, val, sizeof(val)) <= 0)
			return -EIO;
		if (sscanf(val, "%u", &l->index) != 1)
			return -EINVAL;
		snprintf(name, sizeof(name), "%s/%s_type", d->scan_dir,
			 scan_channel[i]);
		if (iio_read_attr_at(d->dfd, name, val, sizeof(val)) <= 0)
			return -EIO;
		ret = iio_scan_parse_type(val, l);
		if (ret)
			return ret;
	}

	*what = "scan element indices";
	ret = iio_scan_layout(d->layout, IIO_SCAN_CHANNELS);
	if (ret < 0)
		return ret;
	if (ret > IIO_SAMPLE_MAX)
		return -E2BIG;
	d->sample_bytes = (unsigned int)ret;

	return 0;
}

static int iio_step2(struct ftest_ctx *x)
{
	struct iio_test_dev *d = x->dev;
	enum iio_selftest_verdict verdict = IIO_SELFTEST_NONE;
	char val[IIO_ATTR_MAX];
	int ret;

	ftest_skip(x, "2-4.int2", "INT2 pin check (D11)", "the driver does not use INT2");
	if (find_magn(x))
		return 0;
	ret = iio_write_attr(d->magn, "selftest", "1");
	if (!ftest_judge(x, "2-4.drdy", "measurement completes", !ret,
			 "the driver's selftest runs both measurements",
			 "%s/selftest: %s", d->magn, ret ? strerror(-ret) : "done"))
		return 0;
	ret = iio_read_attr(d->magn, "selftest", val, sizeof(val));
	if (ret < 0)
		return ftest_io_failed(x, "2-15", "selftest result", ret);
	if (!ftest_judge(x, "2-15.verdict", "self-test verdict readable",
			 !iio_parse_selftest_verdict(val, &verdict) &&
			 verdict != IIO_SELFTEST_NONE, "pass|fail after a test",
			 "\"%s\"", val))
		return 0;
	judge_selftest(x, verdict == IIO_SELFTEST_PASS);

	return 0;
}

/* An attribute of the buffer's set-up, read; its failure fails 3-1 */
static int read_setup_attr(struct ftest_ctx *x, const char *name, char *val,
			   size_t size)
{
	struct iio_test_dev *d = x->dev;
	int ret = iio_read_attr_at(d->dfd, name, val, size);

	return ret < 0 ? ftest_io_failed(x, "3-1", name, ret) : 0;
}

/* The fastest rate the driver offers now, as text into @rate */
static int fastest_rate(struct ftest_ctx *x, char *rate, size_t size)
{
	char val[IIO_ATTR_MAX];
	long hz;
	int ret;

	ret = read_setup_attr(x, "sampling_frequency_available", val,
			      sizeof(val));
	if (ret)
		return ret;
	ret = iio_parse_rate_max(val, IIO_TEST_RATE_MAX_HZ, &hz);
	if (ret) {
		report_add(&x->res->report, "3-1", "sampling_frequency_available",
			   JUDGMENT_FAIL, NULL, "\"%s\": %s", val,
			   iio_value_strerror(ret));
		x->stop = true;
		return ret;
	}
	snprintf(rate, size, "%ld", hz);

	return 0;
}

/* The buffer as the test uses it: its channels, trigger, length and rate */
static int buffer_setup(struct ftest_ctx *x)
{
	struct iio_test_dev *d = x->dev;
	char rate[IIO_NAME_MAX];
	const char *what;
	int ret;

	ret = scan_enable(d);
	if (ret)
		return ftest_io_failed(x, "3-1", "scan elements", ret);
	if (!d->sample_bytes) {
		ret = scan_layout(d, &what);
		if (ret)
			return ftest_io_failed(x, "3-1", what, ret);
	}
	ret = fastest_rate(x, rate, sizeof(rate));
	if (ret)
		return ret;
	ret = change_attr(d, IIO_TRIGGER_ATTR, d->trigger);
	if (!ret)
		ret = change_attr(d, "buffer/length", IIO_TEST_BUFFER_LEN);
	if (!ret)
		ret = change_attr(d, "sampling_frequency", rate);
	if (ret)
		return ftest_io_failed(x, "3-1", "buffer set-up", ret);

	return 0;
}

static int iio_level_setup(struct ftest_ctx *x)
{
	struct iio_test_dev *d = x->dev;
	struct saved_attr *current;
	int ret;

	ret = change_attr(d, IIO_OVERSAMPLING_ATTR,
			  x->o->lpf ? IIO_OVERSAMPLING_ALPF : IIO_OVERSAMPLING_OFF);
	if (ret)
		return ftest_io_failed(x, "3-1", IIO_OVERSAMPLING_ATTR, ret);
	d->comp.ee = x->res->ee;
	/*
	 * Saved now, before the buffer's set-up writes it: the value as found
	 * may name the device's own trigger already
	 */
	ret = save_attr(d, IIO_TRIGGER_ATTR, &current);
	if (ret < 0)
		return ftest_io_failed(x, "3-1", IIO_TRIGGER_ATTR, ret);
	ret = find_trigger(d, current->value);
	if (!ftest_judge(x, "3-1.trigger", "data-ready trigger", !ret,
			 "the driver's INT1 trigger exists",
			 *d->trigger ? "%s" :
			 "none: INT1 is not wired to the driver (%s); use --backend raw",
			 *d->trigger ? d->trigger : d->dir))
		return -ENODEV;

	return buffer_setup(x);
}

/*
 * Read @n samples from the capture into @r, each taken back to the chip's
 * own output: -ERANGE with @why for a sample that cannot be taken back,
 * -ETIMEDOUT when no sample comes for IIO_SAMPLE_STALL_MS
 */
static int read_samples(struct ftest_ctx *x, uint32_t n, struct level_run *r,
			char *why, size_t whylen)
{
	struct iio_test_dev *d = x->dev;
	uint8_t buf[IIO_READ_SAMPLES * IIO_SAMPLE_MAX];
	uint64_t deadline = iio_now_ns(x) + IIO_SAMPLE_STALL_MS * NS_PER_MS;
	size_t have = 0, used;

	while (r->n < n) {
		struct pollfd pfd = { .fd = d->capture_fd, .events = POLLIN };
		uint64_t now = iio_now_ns(x);
		ssize_t got;

		if (now >= deadline)
			return -ETIMEDOUT;
		if (poll(&pfd, 1, (int)((deadline - now) / NS_PER_MS) + 1) < 0) {
			if (errno == EINTR)
				continue;
			return -errno;
		}
		got = read(d->capture_fd, buf + have, sizeof(buf) - have);
		if (got < 0) {
			if (errno == EAGAIN || errno == EINTR)
				continue;
			return -errno;
		}
		have += (size_t)got;
		for (used = 0; have - used >= d->sample_bytes && r->n < n;
		     used += d->sample_bytes) {
			const uint8_t *p = buf + used;
			struct chip_sample cs = { 0 };
			int16_t out[AS9888_AXES];
			int axis;

			deadline = iio_now_ns(x) + IIO_SAMPLE_STALL_MS * NS_PER_MS;
			for (axis = 0; axis < AS9888_AXES; axis++)
				out[axis] = (int16_t)iio_scan_value(&d->layout[axis], p);
			cs.tmps = (uint8_t)iio_scan_value(&d->layout[IIO_SCAN_TEMP], p);
			if (accel_raw_recover(&d->comp, out, cs.tmps, cs.acc, why,
					      whylen))
				return -ERANGE;
			level_run_add(r, &cs);
		}
		memmove(buf, buf + used, have - used);
		have -= used;
	}

	return 0;
}

/* The test's capture ends: the buffer off, the character device closed */
static void capture_stop(struct iio_test_dev *d)
{
	if (d->capture_fd < 0)
		return;
	iio_attr_write(&d->enable, "0");
	close(d->capture_fd);
	d->capture_fd = -1;
}

/*
 * Drop the samples the capture holds: after a DAC write returned, those
 * were measured before it (the driver writes the DAC in the gap between two
 * samples, once the sample before the gap is in the buffer), and every
 * later one after it. 0, -EOVERFLOW when it does not run dry, or -errno
 */
static int drain(struct iio_test_dev *d)
{
	uint8_t buf[IIO_READ_SAMPLES * IIO_SAMPLE_MAX];
	unsigned int reads = 0;
	ssize_t got;

	do {
		if (reads++ == IIO_DRAIN_READS_MAX)
			return -EOVERFLOW;
		got = read(d->capture_fd, buf, sizeof(buf));
	} while (got > 0 || (got < 0 && errno == EINTR));

	return got < 0 && errno != EAGAIN ? -errno : 0;
}

/* The capture started: the character device open, the buffer on */
static int capture_start(struct ftest_ctx *x, const char *step)
{
	struct iio_test_dev *d = x->dev;
	int fd, ret;

	/* a program that took the device since step 1-4 stops the test too */
	fd = open(d->chardev, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
	if (fd < 0 && errno == EBUSY)
		return device_taken(x, step, "character device free",
				    "not open elsewhere");
	if (fd < 0)
		return ftest_io_failed(x, step, d->chardev, -errno);
	ret = iio_attr_write(&d->enable, "1");
	if (ret) {
		close(fd);
		if (ret == -EBUSY)
			return device_taken(x, step, "buffer free",
					    "not enabled elsewhere");
		return ftest_io_failed(x, step, "buffer/enable", ret);
	}
	d->capture_fd = fd;

	return 0;
}

/*
 * @n samples measured from now on into @r, the capture started when it is
 * not running: -ETIMEDOUT when it stalls, with *@taken set when the buffer
 * was found off (another program turned it off); the capture stops on any
 * error
 */
static int collect_once(struct ftest_ctx *x, uint32_t n, const char *step,
			struct level_run *r, char *why, size_t whylen,
			bool *taken)
{
	struct iio_test_dev *d = x->dev;
	char val[IIO_ATTR_MAX];
	int ret;

	level_run_init(r);
	r->status_by_driver = true;
	*taken = false;
	if (d->capture_fd < 0) {
		ret = capture_start(x, step);
		if (ret)
			return ret;
	}
	ret = read_samples(x, n, r, why, whylen);
	if (ret == -ETIMEDOUT && iio_attr_read(&d->enable, val, sizeof(val)) > 0)
		*taken = !strcmp(val, "0");
	if (ret)
		capture_stop(d);

	return ret;
}

#define INT1_LIMITS "the data-ready trigger fires on INT1"

/*
 * D11's INT1 check, made once, at the first level run: the pin rises when
 * the data-ready trigger, which only INT1 fires, delivers the run's @n
 * samples (@delivered); it fails when the trigger went silent before
 * (@got of @n, then none within the stall time; a buffer another program
 * turned off is no verdict on the pin and is judged on its own)
 */
static void iio_judge_int1(struct ftest_ctx *x, const char *step,
			   bool delivered, uint32_t got, uint32_t n)
{
	struct iio_test_dev *d = x->dev;
	char id[JUDGMENT_ID_LEN];

	if (d->int1_seen)
		return;
	d->int1_seen = true;
	snprintf(id, sizeof(id), "%s.int1", step);
	if (delivered)
		ftest_judge(x, id, "INT1 pin check (D11)", true, INT1_LIMITS,
			    "%u of %u samples from %s", got, n, d->trigger);
	else
		ftest_judge(x, id, "INT1 pin check (D11)", false, INT1_LIMITS,
			    "%u of %u samples from %s, then none for %u ms",
			    got, n, d->trigger, IIO_SAMPLE_STALL_MS);
}

static int iio_level_collect(struct ftest_ctx *x, uint32_t n, const char *step,
			     struct level_run *r)
{
	struct iio_test_dev *d = x->dev;
	char id[JUDGMENT_ID_LEN];
	char why[JUDGMENT_TEXT_LEN];
	unsigned int retakes = 0;
	bool taken;
	int ret;

	/* the calibbias in effect: read back with the last DAC written */
	memcpy(d->comp.da, x->dac, AS9888_AXES);
	for (;;) {
		ret = collect_once(x, n, step, r, why, sizeof(why), &taken);
		if (ret != -ETIMEDOUT || !taken || retakes == IIO_RETAKE_MAX)
			break;
		/* the run starts again with the test's own set-up */
		retakes++;
		ret = buffer_setup(x);
		if (ret)
			return ret;
	}
	if (x->stop)
		return ret;

	if (ret == -ERANGE) {
		ftest_judge(x, step, "chip's own reading recovered", false,
			    "compensated sample within the driver's output",
			    "sample %u: %s", r->n, why);
		x->stop = true;
		return ret;
	}
	snprintf(id, sizeof(id), "%s.delivered", step);
	if (ret == -ETIMEDOUT && taken) {
		ftest_judge(x, id, "buffer kept for the run", false,
			    "no other program turns it off",
			    "another program turned the buffer off %u times (libiio clients do as they start): stop it and run again",
			    retakes + 1);
		x->stop = true;
		return ret;
	}
	if (ret == -ETIMEDOUT) {
		iio_judge_int1(x, step, false, r->n, n);
		ftest_judge(x, id, "samples delivered (INT1, ST1, EMPT)", false,
			    "N samples from the data-ready trigger",
			    "%u of %u, then none for %u ms: INT1 silent or samples failing the driver's checks (see the kernel log)",
			    r->n, n, IIO_SAMPLE_STALL_MS);
		x->stop = true;
		return ret;
	}
	if (ret)
		return ftest_io_failed(x, step, d->chardev, ret);
	iio_judge_int1(x, step, true, r->n, n);

	return 0;
}

static int iio_level_dac(struct ftest_ctx *x, const uint8_t dac[AS9888_AXES])
{
	struct iio_test_dev *d = x->dev;
	bool same;
	int ret;

	ret = put_dac(x, dac, "3-26", &same);
	if (ret)
		return ret;
	/* what the running capture holds was measured with the DAC before */
	ret = d->capture_fd >= 0 ? drain(d) : 0;
	if (ret) {
		capture_stop(d);
		return ftest_io_failed(x, "3-26", d->chardev, ret);
	}
	ftest_judge(x, "3-26", "DAC written (3-24..3-26, D2)", same,
		    "read-back equals DACopt", "0x%02x 0x%02x 0x%02x",
		    x->dac[0], x->dac[1], x->dac[2]);

	return 0;
}

/* Put every changed attribute back, in the order they were saved */
static void iio_finish(struct ftest_ctx *x)
{
	struct iio_test_dev *d = x->dev;
	unsigned int i;

	/*
	 * The test's own capture ends first (scan elements, trigger and
	 * length change only with the buffer off); a buffer the test did not
	 * enable is not touched: when the test stopped because another
	 * program was capturing, that capture goes on
	 */
	capture_stop(d);
	for (i = 0; i < d->n_saved; i++) {
		const struct saved_attr *a = &d->saved[i];

		if (!a->changed)
			continue;
		if (iio_attr_write(&a->file, a->value))
			fprintf(stderr, "as9888-calibd: %s/%s: cannot put back \"%s\"\n",
				d->dir, a->name, a->value);
	}
}

/*
 * calibbias as found, put back whatever the test does (step 1 writes the
 * DAC through it); *@failed names a failure
 */
static int save_calibration(struct iio_test_dev *d, const char **failed)
{
	struct saved_attr *a;
	int axis, ret;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		ret = save_attr(d, iio_calibbias_attr[axis], &a);
		if (ret < 0) {
			*failed = iio_calibbias_attr[axis];
			return ret;
		}
		a->changed = true;
		d->calibbias[axis] = a->file;
	}

	return 0;
}

static const struct ftest_device_ops iio_ops = {
	.step1 = iio_step1,
	.step2 = iio_step2,
	.level_setup = iio_level_setup,
	.level_collect = iio_level_collect,
	.write_dac = iio_level_dac,
	.finish = iio_finish,
	.now_ns = iio_now_ns,
	.sleep_ns = iio_sleep_ns,
};

int ftest_run_iio(const char *dir, const struct ftest_opts *o,
		  struct ftest_result *res)
{
	struct iio_test_dev *d;
	struct ftest_ctx x = { .ops = &iio_ops, .o = o, .res = res };
	char probe[IIO_PATH_MAX];
	const char *base = strrchr(dir, '/'), *failed;
	unsigned int i;
	int ret;

	if (!base || strncmp(base + 1, IIO_DEVICE_PREFIX, strlen(IIO_DEVICE_PREFIX)))
		return -EINVAL;
	d = calloc(1, sizeof(*d));
	if (!d)
		return -ENOMEM;
	d->enable = IIO_ATTR_CLOSED;
	d->capture_fd = -1;
	snprintf(d->dir, sizeof(d->dir), "%s", dir);
	snprintf(d->chardev, sizeof(d->chardev), "%s/%s", iio_dev_root(), base + 1);
	/* scan_elements/ on every kernel; buffer0/ holds the same files */
	snprintf(probe, sizeof(probe), "%s/scan_elements", dir);
	d->scan_dir = access(probe, F_OK) ? "buffer0" : "scan_elements";

	/*
	 * The DAC and the calibration are saved before anything changes;
	 * the rest before its own first change
	 */
	d->dfd = iio_dir_open(dir);
	failed = ".";
	ret = d->dfd < 0 ? d->dfd : save_calibration(d, &failed);
	if (ret) {
		report_add(&res->report, "1-4", "device attributes", JUDGMENT_FAIL,
			   NULL, "%s/%s: %s", dir, failed, strerror(-ret));
		goto out;
	}
	x.dev = d;
	ret = ftest_engine_run(&x);
out:
	capture_stop(d);
	for (i = 0; i < d->n_saved; i++)
		iio_attr_close(&d->saved[i].file);
	iio_attr_close(&d->enable);
	if (d->dfd >= 0)
		close(d->dfd);
	free(d);

	return ret;
}
