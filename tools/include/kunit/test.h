/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Userspace stand-in for <kunit/test.h>: the part the driver's KUnit tests
 * use (EXPECT/ASSERT of integers, truth and strings, cases with array
 * parameters, one suite), so that the same test file also builds and runs
 * as an ordinary program (tests/calib, "calib-kunit"). kunit_test_suite()
 * makes the program's main(): every case (each parameter of a
 * parameterised one) is counted first and the TAP plan printed, then each
 * runs and prints ok or not ok, with the failed expectations as
 * diagnostics; the exit status is 1 when any failed. A failed ASSERT ends
 * its case, as in the kernel.
 */
#ifndef AS9888_SHIM_KUNIT_TEST_H
#define AS9888_SHIM_KUNIT_TEST_H

#include <limits.h>	/* INT_MAX: the kernel's <kunit/test.h> brings it in */
#include <setjmp.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include <kunit/visibility.h>
#include <linux/kernel.h>
#include <linux/module.h>

#define KUNIT_PARAM_DESC_SIZE	128

struct kunit {
	const void *param_value;
	bool failed;
	jmp_buf abort;
};

struct kunit_case {
	void (*run_case)(struct kunit *test);
	const char *name;
	const void *(*generate_params)(const void *prev, char *desc);
};

struct kunit_suite {
	const char *name;
	struct kunit_case *test_cases;
};

#define KUNIT_CASE(fn)	{ .run_case = fn, .name = #fn }
#define KUNIT_CASE_PARAM(fn, gen) \
	{ .run_case = fn, .name = #fn, .generate_params = gen }

/* NAME_gen_params(): the elements of ARRAY one after the other */
#define KUNIT_ARRAY_PARAM(name, array, get_desc)				\
	static const void *name##_gen_params(const void *prev, char *desc)	\
	{									\
		__typeof__((array)[0]) *__next = prev ?				\
			((__typeof__((array)[0]) *)prev) + 1 : (array);		\
		if (__next - (array) < (long)ARRAY_SIZE(array)) {		\
			void (*__get_desc)(__typeof__(__next), char *) = get_desc; \
			if (__get_desc)						\
				__get_desc(__next, desc);			\
			return __next;						\
		}								\
		return NULL;							\
	}

static inline void kunit_user_failed(struct kunit *test, const char *file,
				     int line, const char *what)
{
	test->failed = true;
	printf("# %s:%d: %s\n", file, line, what);
}

#define KUNIT_USER_INT(test, left, right, assert) do {			\
	long long __l = (long long)(left), __r = (long long)(right);	\
	if (__l != __r) {						\
		char __what[256];					\
		snprintf(__what, sizeof(__what),			\
			 "expected %s == %s, got %lld and %lld",	\
			 #left, #right, __l, __r);			\
		kunit_user_failed(test, __FILE__, __LINE__, __what);	\
		if (assert)						\
			longjmp((test)->abort, 1);			\
	}								\
} while (0)

#define KUNIT_USER_TRUE(test, cond, want) do {				\
	if (!!(cond) != (want)) {					\
		kunit_user_failed(test, __FILE__, __LINE__,		\
				  "expected " #cond " to be " #want);	\
	}								\
} while (0)

#define KUNIT_EXPECT_EQ(test, left, right) KUNIT_USER_INT(test, left, right, 0)
#define KUNIT_ASSERT_EQ(test, left, right) KUNIT_USER_INT(test, left, right, 1)
#define KUNIT_EXPECT_TRUE(test, cond)	KUNIT_USER_TRUE(test, cond, true)
#define KUNIT_EXPECT_FALSE(test, cond)	KUNIT_USER_TRUE(test, cond, false)
#define KUNIT_EXPECT_STREQ(test, left, right) do {			\
	const char *__l = (left), *__r = (right);			\
	if (strcmp(__l, __r)) {						\
		char __what[512];					\
		snprintf(__what, sizeof(__what),			\
			 "expected %s == \"%s\", got \"%s\"",		\
			 #left, __r, __l);				\
		kunit_user_failed(test, __FILE__, __LINE__, __what);	\
	}								\
} while (0)

/* One run of @c (with @param): its TAP line as number @n */
static inline bool kunit_user_run_one(const struct kunit_case *c,
				      const void *param, const char *desc,
				      unsigned int n)
{
	struct kunit test = { .param_value = param };

	if (!setjmp(test.abort))
		c->run_case(&test);
	printf("%s %u - %s%s%s%s\n", test.failed ? "not ok" : "ok", n, c->name,
	       param ? " [" : "", param ? desc : "", param ? "]" : "");

	return !test.failed;
}

/* Every case of @s, @run: count them (0) or run them (1); the failures */
static inline unsigned int kunit_user_cases(const struct kunit_suite *s,
					    bool run, unsigned int *n)
{
	unsigned int failed = 0;
	const struct kunit_case *c;

	for (c = s->test_cases; c->run_case; c++) {
		char desc[KUNIT_PARAM_DESC_SIZE] = "";
		const void *p = NULL;

		if (!c->generate_params) {
			++*n;
			if (run && !kunit_user_run_one(c, NULL, desc, *n))
				failed++;
			continue;
		}
		while ((p = c->generate_params(p, desc))) {
			++*n;
			if (run && !kunit_user_run_one(c, p, desc, *n))
				failed++;
			desc[0] = '\0';
		}
	}

	return failed;
}

static inline int kunit_user_main(const struct kunit_suite *s)
{
	unsigned int n = 0, failed;

	kunit_user_cases(s, false, &n);
	printf("# %s (userspace build of the KUnit cases)\n1..%u\n", s->name, n);
	n = 0;
	failed = kunit_user_cases(s, true, &n);
	printf("# %u of %u failed\n", failed, n);

	return failed ? 1 : 0;
}

#define kunit_test_suite(suite) \
	int main(void) { return kunit_user_main(&(suite)); }

#endif
