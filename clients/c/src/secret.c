/* The bus's secret and the message codes: see secret.h. */
#define _GNU_SOURCE
#include "secret.h"

#include <errno.h>
#include <fcntl.h>
#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/hmac.h>
#include <pwd.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#define MAX_KEY_FILE (64 * 1024)
/* A sender that had nothing accepted for this long is forgotten: a message of it replayed now would be stale. */
#define FORGET_NS (2 * DTRON_STALE_NS)
#define WORDS (DTRON_REPLAY_WINDOW / 64)

typedef struct {
    char *sender;
    uint64_t highest;
    uint64_t seen[WORDS]; /* bit i: highest - i was accepted */
    int64_t last_ns;
} window;

struct dtron_guard {
    uint8_t key[32];
    uint64_t sequence;
    window *windows;
    size_t nwindows, capacity;
    int64_t forget_at;
};

const char *dtron_drop_reason(int reason) {
    switch (reason) {
    case DTRON_DROP_UNAUTHENTICATED: return "UNAUTHENTICATED";
    case DTRON_DROP_REPLAYED: return "REPLAYED";
    case DTRON_DROP_STALE: return "STALE";
    default: return "NONE";
    }
}

/* ---- the key file ---- */

static int refuse(char *err, size_t errlen, const char *format, const char *path, const char *detail) {
    if (err && errlen) {
        snprintf(err, errlen, format, path, detail);
    }
    return -1;
}

int dtron_default_key_file(char *path, size_t size) {
    const char *home = getenv("DTRON_HOME");
    int n;
    if (home && *home) {
        n = snprintf(path, size, "%s/bus.key", home);
    } else {
        const char *user_home = getenv("HOME");
        if (user_home == NULL || *user_home == '\0') {
            struct passwd *entry = getpwuid(getuid());
            user_home = entry ? entry->pw_dir : "/";
        }
        n = snprintf(path, size, "%s/.dtron/bus.key", user_home);
    }
    return n < 0 || (size_t)n >= size ? -1 : 0;
}

static int read_key(const char *path, uint8_t **secret, size_t *length, char *err, size_t errlen) {
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
        return errno == ENOENT ? refuse(err, errlen, "key file %s does not exist%s", path, "")
                               : refuse(err, errlen, "key file %s cannot be read: %s", path, strerror(errno));
    }
    struct stat info;
    char mode[16];
    if (fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
        close(fd);
        return refuse(err, errlen, "key file %s is not a regular file%s", path, "");
    }
    if (info.st_mode & 066) {
        close(fd);
        snprintf(mode, sizeof mode, "%o", (unsigned)(info.st_mode & 0777));
        if (err && errlen) {
            snprintf(err, errlen, "key file %s may be read or written by group or others (mode %s): chmod 600 %s",
                     path, mode, path);
        }
        return -1;
    }
    char *content = malloc(MAX_KEY_FILE + 1);
    size_t got = 0;
    ssize_t n;
    while (content && got <= MAX_KEY_FILE && (n = read(fd, content + got, MAX_KEY_FILE + 1 - got)) > 0) {
        got += (size_t)n;
    }
    close(fd);
    if (content == NULL || got > MAX_KEY_FILE) {
        free(content);
        return refuse(err, errlen, "key file %s is longer than 65536 bytes%s", path, "");
    }
    size_t start = 0, end = got;
    while (start < end && strchr(" \t\n\v\f\r", content[start]) && content[start]) {
        start++;
    }
    while (end > start && strchr(" \t\n\v\f\r", content[end - 1]) && content[end - 1]) {
        end--;
    }
    if (end == start) {
        free(content);
        return refuse(err, errlen, "key file %s is empty%s", path, "");
    }
    *length = end - start;
    *secret = malloc(*length);
    memcpy(*secret, content + start, *length);
    OPENSSL_cleanse(content, got);
    free(content);
    return 0;
}

/* mkdir -p with mode 0700 for the folders it makes. */
static int make_folders(char *path) {
    for (char *slash = strchr(path + 1, '/');; slash = strchr(slash + 1, '/')) {
        if (slash) {
            *slash = '\0';
        }
        int made = mkdir(path, 0700) == 0 || errno == EEXIST;
        if (slash) {
            *slash = '/';
        }
        if (!made) {
            return -1;
        }
        if (!slash) {
            return 0;
        }
    }
}

/* Makes the default key file: a temporary file with mode 0600 holding 64 random hexadecimal digits, linked to the
 * final name; if another member linked one first, that one stays. */
static int create_key(const char *path, char *err, size_t errlen) {
    char folder[4096], temporary[4200];
    uint8_t random[36];
    char text[66];
    snprintf(folder, sizeof folder, "%s", path);
    char *slash = strrchr(folder, '/');
    if (slash == NULL) {
        snprintf(folder, sizeof folder, ".");
    } else if (slash == folder) {
        folder[1] = '\0';
    } else {
        *slash = '\0';
    }
    if (make_folders(folder) != 0) {
        return refuse(err, errlen, "cannot make the folder of key file %s: %s", path, strerror(errno));
    }
    if (getrandom(random, sizeof random, 0) != (ssize_t)sizeof random) {
        return refuse(err, errlen, "cannot make key file %s: no random bytes: %s", path, strerror(errno));
    }
    for (size_t i = 0; i < 32; i++) {
        snprintf(text + 2 * i, 3, "%02x", random[i]);
    }
    unsigned tag = (unsigned)random[32] << 24 | (unsigned)random[33] << 16 | (unsigned)random[34] << 8 | random[35];
    text[64] = '\n';
    text[65] = '\0';
    OPENSSL_cleanse(random, sizeof random);
    snprintf(temporary, sizeof temporary, "%s/.bus.key.%d.%08x", folder, (int)getpid(), tag);
    int fd = open(temporary, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0) {
        return refuse(err, errlen, "cannot make key file %s: %s", path, strerror(errno));
    }
    int ok = fchmod(fd, 0600) == 0 && write(fd, text, 65) == 65 && fsync(fd) == 0;
    int error = errno;
    OPENSSL_cleanse(text, sizeof text);
    ok &= close(fd) == 0;
    if (ok && link(temporary, path) != 0 && errno != EEXIST) { /* EEXIST: another member made it first */
        error = errno;
        ok = 0;
    }
    unlink(temporary);
    return ok ? 0 : refuse(err, errlen, "cannot make key file %s: %s", path, strerror(error));
}

int dtron_load_secret(const char *key_file, uint8_t **secret, size_t *length, char *err, size_t errlen) {
    char path[4096];
    if (key_file != NULL) {
        return read_key(key_file, secret, length, err, errlen);
    }
    if (dtron_default_key_file(path, sizeof path) != 0) {
        return refuse(err, errlen, "the default key file's path is too long: %s%s", path, "");
    }
    if (access(path, F_OK) != 0 && errno == ENOENT && create_key(path, err, errlen) != 0) {
        return -1;
    }
    return read_key(path, secret, length, err, errlen);
}

/* ---- codes ---- */

void dtron_mac_key(const uint8_t *secret, size_t length, uint8_t key[32]) {
    static const char label[] = "dtron-bus-mac-v1";
    unsigned int size = 32;
    HMAC(EVP_sha256(), secret, (int)length, (const unsigned char *)label, sizeof label - 1, key, &size);
}

static uint8_t *item(uint8_t *at, const void *bytes, size_t length) {
    at[0] = (uint8_t)(length >> 24);
    at[1] = (uint8_t)(length >> 16);
    at[2] = (uint8_t)(length >> 8);
    at[3] = (uint8_t)length;
    if (length) {
        memcpy(at + 4, bytes, length);
    }
    return at + 4 + length;
}

void dtron_message_code(const uint8_t key[32], const char *subject, const char *sender, const char *seq,
                        const char *time, const char *presence, const char *joined, const void *data, size_t length,
                        char code[65]) {
    const char *texts[] = {subject, sender, seq, time, presence, joined};
    size_t total = 4 + length;
    for (size_t i = 0; i < 6; i++) {
        total += 4 + (texts[i] ? strlen(texts[i]) : 0);
    }
    uint8_t *m = malloc(total), *at = m;
    for (size_t i = 0; i < 6; i++) {
        at = item(at, texts[i], texts[i] ? strlen(texts[i]) : 0);
    }
    item(at, data, length);
    uint8_t mac[32];
    unsigned int size = 32;
    HMAC(EVP_sha256(), key, 32, m, total, mac, &size);
    free(m);
    for (size_t i = 0; i < 32; i++) {
        snprintf(code + 2 * i, 3, "%02x", mac[i]);
    }
}

/* ---- the guard ---- */

dtron_guard *dtron_guard_create(const uint8_t *secret, size_t length, uint64_t first_number) {
    dtron_guard *guard = calloc(1, sizeof *guard);
    if (guard != NULL) {
        dtron_mac_key(secret, length, guard->key);
        guard->sequence = first_number - 1;
    }
    return guard;
}

void dtron_guard_free(dtron_guard *guard) {
    if (guard == NULL) {
        return;
    }
    for (size_t i = 0; i < guard->nwindows; i++) {
        free(guard->windows[i].sender);
    }
    free(guard->windows);
    OPENSSL_cleanse(guard->key, sizeof guard->key);
    free(guard);
}

void dtron_guard_sign(dtron_guard *guard, const char *subject, const char *sender, const char *presence,
                      const char *joined, const void *data, size_t length, int64_t now_ns, char *seq, char *time,
                      char code[65]) {
    snprintf(seq, 21, "%llu", (unsigned long long)++guard->sequence);
    snprintf(time, 21, "%lld", (long long)now_ns);
    dtron_message_code(guard->key, subject, sender, seq, time, presence, joined, data, length, code);
}

/* A decimal number that fits into an int64_t, or -1. */
static int64_t decimal(const char *text) {
    if (text == NULL || *text == '\0') {
        return -1;
    }
    int64_t value = 0;
    for (const char *c = text; *c; c++) {
        if (*c < '0' || *c > '9' || value > (INT64_MAX - (*c - '0')) / 10) {
            return -1;
        }
        value = value * 10 + (*c - '0');
    }
    return value;
}

static int seen(const window *w, uint64_t behind) {
    return (int)((w->seen[behind / 64] >> (behind % 64)) & 1);
}

static void accept_number(window *w, uint64_t number, int64_t stream_ns) {
    if (number > w->highest) {
        uint64_t shift = number - w->highest;
        size_t words = shift >= DTRON_REPLAY_WINDOW ? WORDS : (size_t)(shift / 64), bits = (size_t)(shift % 64);
        for (size_t i = WORDS; i-- > 0;) { /* bit b moves to bit b + shift */
            uint64_t value = 0;
            if (i >= words) {
                value = w->seen[i - words] << bits;
                if (bits && i - words >= 1) {
                    value |= w->seen[i - words - 1] >> (64 - bits);
                }
            }
            w->seen[i] = value;
        }
        w->highest = number;
    }
    uint64_t behind = w->highest - number;
    w->seen[behind / 64] |= 1ULL << (behind % 64);
    if (stream_ns > w->last_ns) {
        w->last_ns = stream_ns;
    }
}

/* Forgets the senders that had nothing accepted for FORGET_NS (looked at most every DTRON_STALE_NS). */
static void forget(dtron_guard *guard, int64_t stream_ns) {
    if (stream_ns < guard->forget_at) {
        return;
    }
    guard->forget_at = stream_ns + DTRON_STALE_NS;
    for (size_t i = 0; i < guard->nwindows;) {
        if (guard->windows[i].last_ns < stream_ns - FORGET_NS) {
            free(guard->windows[i].sender);
            guard->windows[i] = guard->windows[--guard->nwindows];
        } else {
            i++;
        }
    }
}

static int authentic(const dtron_guard *guard, const char *subject, const char *sender, const char *seq,
                     const char *time, const char *presence, const char *joined, const char *mac, const void *data,
                     size_t length) {
    char code[65];
    if (mac == NULL || strlen(mac) != 64) {
        return 0;
    }
    dtron_message_code(guard->key, subject, sender, seq, time, presence, joined, data, length, code);
    return CRYPTO_memcmp(code, mac, 64) == 0;
}

/* The window of a sender ("" for none), or NULL when it has none. */
static window *window_of(dtron_guard *guard, const char *name) {
    for (size_t i = 0; i < guard->nwindows; i++) {
        if (strcmp(guard->windows[i].sender, name) == 0) {
            return &guard->windows[i];
        }
    }
    return NULL;
}

/* A new, empty window of a sender; NULL if out of memory. */
static window *add_window(dtron_guard *guard, const char *name, int64_t stream_ns) {
    forget(guard, stream_ns);
    if (guard->nwindows == guard->capacity) {
        size_t capacity = guard->capacity ? 2 * guard->capacity : 8;
        window *more = realloc(guard->windows, capacity * sizeof *more);
        if (more == NULL) {
            return NULL;
        }
        guard->windows = more;
        guard->capacity = capacity;
    }
    window *w = &guard->windows[guard->nwindows];
    memset(w, 0, sizeof *w);
    w->sender = strdup(name);
    if (w->sender == NULL) {
        return NULL;
    }
    guard->nwindows++;
    return w;
}

/* Whether a number was accepted from the window's sender already, or is too low for the window to tell. */
static int taken(const window *w, uint64_t number) {
    return w != NULL && number <= w->highest
           && (w->highest - number >= DTRON_REPLAY_WINDOW || seen(w, w->highest - number));
}

int dtron_guard_check(dtron_guard *guard, const char *subject, const char *sender, const char *seq, const char *time,
                      const char *presence, const char *joined, const char *mac, const void *data, size_t length,
                      int64_t stream_ns) {
    if (!authentic(guard, subject, sender, seq, time, presence, joined, mac, data, length)) {
        return DTRON_DROP_UNAUTHENTICATED;
    }
    const char *name = sender ? sender : "";
    int64_t number = decimal(seq);
    window *w = window_of(guard, name);
    if (number < 1 || taken(w, (uint64_t)number)) {
        return DTRON_DROP_REPLAYED;
    }
    int64_t sent = decimal(time);
    if (sent < 0 || sent - stream_ns > DTRON_STALE_NS || stream_ns - sent > DTRON_STALE_NS) {
        return DTRON_DROP_STALE;
    }
    if (w == NULL && (w = add_window(guard, name, stream_ns)) == NULL) {
        return DTRON_DROP_REPLAYED; /* cannot remember it: do not take it */
    }
    accept_number(w, (uint64_t)number, stream_ns);
    return DTRON_DROP_NONE;
}

int dtron_guard_learn(dtron_guard *guard, const char *subject, const char *sender, const char *seq, const char *time,
                      const char *presence, const char *joined, const char *mac, const void *data, size_t length,
                      int64_t stream_ns) {
    int64_t number = decimal(seq);
    if (number < 1 || !authentic(guard, subject, sender, seq, time, presence, joined, mac, data, length)) {
        return 0;
    }
    const char *name = sender ? sender : "";
    window *w = window_of(guard, name);
    if (w == NULL && (w = add_window(guard, name, stream_ns)) == NULL) {
        return 0;
    }
    if (!taken(w, (uint64_t)number)) {
        accept_number(w, (uint64_t)number, stream_ns);
    }
    return 1;
}

uint64_t dtron_guard_next_number(const dtron_guard *guard) {
    return guard->sequence + 1;
}
