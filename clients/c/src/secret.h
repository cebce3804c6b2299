/*
 * The bus's secret and the message codes (DTRON's site, page "Security: the bus's secret"); internal to libdtron,
 * not part of dtron.h. The key file: by default $DTRON_HOME/bus.key or ~/.dtron/bus.key, made on first use. Every
 * message carries Dtron-Seq, Dtron-Time and Dtron-Mac = HMAC-SHA256(K, M), K = HMAC-SHA256(secret,
 * "dtron-bus-mac-v1"); every message read is checked: unauthenticated, replayed, stale.
 */
#ifndef DTRON_SECRET_H
#define DTRON_SECRET_H

#include <stddef.h>
#include <stdint.h>

/** Why a message was dropped (0: it was not). */
enum { DTRON_DROP_NONE = 0, DTRON_DROP_UNAUTHENTICATED = 1, DTRON_DROP_REPLAYED = 2, DTRON_DROP_STALE = 3 };

/** The numbers remembered below a sender's highest. */
#define DTRON_REPLAY_WINDOW 4096
/** The most a Dtron-Time may be away from when the stream stored the message. */
#define DTRON_STALE_NS 120000000000LL

/** The signer and checker of one member. */
typedef struct dtron_guard dtron_guard;

/** The name of a reason, as every DTRON member counts it: "UNAUTHENTICATED", "REPLAYED", "STALE". */
const char *dtron_drop_reason(int reason);

/** Writes the default key file's path ($DTRON_HOME/bus.key, else ~/.dtron/bus.key); 0, or -1 if it is too long. */
int dtron_default_key_file(char *path, size_t size);

/**
 * Reads the secret of key_file, or (key_file NULL) of the default key file, which is made if there is none. Returns
 * 0 and a malloc'ed secret, or -1 with a one-line reason naming the file in err.
 */
int dtron_load_secret(const char *key_file, uint8_t **secret, size_t *length, char *err, size_t errlen);

/** K = HMAC-SHA256(secret, "dtron-bus-mac-v1"). */
void dtron_mac_key(const uint8_t *secret, size_t length, uint8_t key[32]);

/** Dtron-Mac: HMAC-SHA256(K, M) in 64 lowercase hexadecimal digits and a NUL; absent headers are NULL. */
void dtron_message_code(const uint8_t key[32], const char *subject, const char *sender, const char *seq,
                        const char *time, const char *presence, const char *joined, const void *data, size_t length,
                        char code[65]);

/**
 * A guard with the key made from secret, whose first message gets number first_number (the wall clock at connecting,
 * in ns, so that a member started again under the same id goes on above the numbers it used before); NULL if out of
 * memory.
 */
dtron_guard *dtron_guard_create(const uint8_t *secret, size_t length, uint64_t first_number);

void dtron_guard_free(dtron_guard *guard);

/**
 * Signs a message: writes this member's next number into seq (at least 21 bytes), now_ns into time (at least 21
 * bytes) and the code into code.
 */
void dtron_guard_sign(dtron_guard *guard, const char *subject, const char *sender, const char *presence,
                      const char *joined, const void *data, size_t length, int64_t now_ns, char *seq, char *time,
                      char code[65]);

/**
 * Checks a message the stream stored at stream_ns (absent headers NULL): DTRON_DROP_NONE (its number is then
 * remembered) or why it is dropped.
 */
int dtron_guard_check(dtron_guard *guard, const char *subject, const char *sender, const char *seq, const char *time,
                      const char *presence, const char *joined, const char *mac, const void *data, size_t length,
                      int64_t stream_ns);

/**
 * Takes note of the number of a message published before this member joined, stored at stream_ns, so that a copy of
 * it published again later is replayed: only a message whose code is valid counts, whatever its time. Returns 1 if
 * it counted, else 0.
 */
int dtron_guard_learn(dtron_guard *guard, const char *subject, const char *sender, const char *seq, const char *time,
                      const char *presence, const char *joined, const char *mac, const void *data, size_t length,
                      int64_t stream_ns);

/** The Dtron-Seq of the next message this member signs. */
uint64_t dtron_guard_next_number(const dtron_guard *guard);

#endif
