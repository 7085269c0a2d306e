// SPDX-License-Identifier: GPL-2.0
/* The HAL's configuration: defaults and "key value" lines (as9888_hal.h) */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "as9888_hal.h"

#define CONFIG_MAX	4096

void as9888_hal_config_defaults(struct as9888_hal_config *cfg)
{
	memset(cfg, 0, sizeof(*cfg));
	strcpy(cfg->sysfs, "/sys");
	strcpy(cfg->dev, "/dev");
	strcpy(cfg->record, "/mnt/vendor/persist/as9888/calibration");
	strcpy(cfg->socket, "/dev/socket/as9888_calibd");
	cfg->feed_interval_ms = 1000;
}

#define STRING_KEY(f)	{ #f, offsetof(struct as9888_hal_config, f), \
			  sizeof(((struct as9888_hal_config *)0)->f) }

static const struct {
	const char *key;
	size_t offset;
	size_t size;
} string_keys[] = {
	STRING_KEY(sysfs), STRING_KEY(dev), STRING_KEY(parent),
	STRING_KEY(trigger), STRING_KEY(record), STRING_KEY(socket),
};

/* One line, without its newline and comment: 0 or -EINVAL */
static int config_line(char *line, struct as9888_hal_config *c, const char **why)
{
	char *key, *value, *end;
	unsigned long ms;
	size_t i;

	key = line + strspn(line, " \t");
	if (!*key)
		return 0;
	value = key + strcspn(key, " \t");
	if (*value)
		*value++ = '\0';
	value += strspn(value, " \t");
	end = value + strlen(value);
	while (end > value && (end[-1] == ' ' || end[-1] == '\t'))
		*--end = '\0';
	if (strchr(value, ' ') || strchr(value, '\t')) {
		*why = "one value without spaces expected";
		return -EINVAL;
	}
	if (!strcmp(key, "feed_interval_ms")) {
		errno = 0;
		ms = strtoul(value, &end, 10);
		if (!*value || *end || errno || *value == '-' || ms < 100 || ms > 60000) {
			*why = "feed_interval_ms takes 100..60000";
			return -EINVAL;
		}
		c->feed_interval_ms = (unsigned int)ms;
		return 0;
	}
	for (i = 0; i < sizeof(string_keys) / sizeof(string_keys[0]); i++) {
		if (strcmp(key, string_keys[i].key))
			continue;
		if (strlen(value) >= string_keys[i].size) {
			*why = "value too long";
			return -EINVAL;
		}
		strcpy((char *)c + string_keys[i].offset, value);
		return 0;
	}
	*why = "unknown key (sysfs, dev, parent, trigger, record, socket, feed_interval_ms)";
	return -EINVAL;
}

int as9888_hal_config_parse(const char *text, struct as9888_hal_config *cfg,
			    char *err, size_t errlen)
{
	struct as9888_hal_config c = *cfg;
	char line[512];
	const char *why = NULL;
	unsigned int lineno = 0;
	size_t len;

	while (*text) {
		lineno++;
		len = strcspn(text, "\n");
		if (len >= sizeof(line)) {
			snprintf(err, errlen, "line %u: longer than %zu bytes", lineno,
				 sizeof(line) - 1);
			return -EINVAL;
		}
		memcpy(line, text, len);
		line[len] = '\0';
		text += len + (text[len] == '\n');
		line[strcspn(line, "#")] = '\0';
		if (config_line(line, &c, &why)) {
			snprintf(err, errlen, "line %u: %s", lineno, why);
			return -EINVAL;
		}
	}
	*cfg = c;
	return 0;
}

int as9888_hal_config_load(const char *path, struct as9888_hal_config *cfg,
			   char *err, size_t errlen)
{
	char text[CONFIG_MAX + 1], why[200];
	ssize_t n;
	int fd, ret;

	fd = open(path, O_RDONLY | O_CLOEXEC);
	if (fd < 0) {
		ret = -errno;
		snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
		return ret;
	}
	n = read(fd, text, sizeof(text));
	ret = n < 0 ? -errno : 0;
	close(fd);
	if (ret) {
		snprintf(err, errlen, "%s: cannot read: %s", path, strerror(-ret));
		return ret;
	}
	if (n > CONFIG_MAX || memchr(text, '\0', (size_t)n)) {
		snprintf(err, errlen, "%s: %s", path, n > CONFIG_MAX ?
			 "longer than 4096 bytes" : "holds a NUL byte");
		return -EINVAL;
	}
	text[n] = '\0';
	ret = as9888_hal_config_parse(text, cfg, why, sizeof(why));
	if (ret)
		snprintf(err, errlen, "%s: %s", path, why);
	return ret;
}
