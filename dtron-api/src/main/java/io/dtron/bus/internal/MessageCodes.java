package io.dtron.bus.internal;

import java.nio.charset.StandardCharsets;
import java.security.GeneralSecurityException;
import java.security.MessageDigest;
import java.util.HashMap;
import java.util.HexFormat;
import java.util.Map;
import java.util.Objects;
import javax.crypto.Mac;
import javax.crypto.spec.SecretKeySpec;

/**
 * Not API. The message codes of a NATS bus (security.md, "Over NATS"): the key {@code K} derived from the bus's
 * secret, and the code {@code HMAC-SHA256(K, M)} of a message, {@code M} being the subject, {@code Dtron-Sender},
 * {@code Dtron-Seq}, {@code Dtron-Time}, {@code Dtron-Presence}, {@code Dtron-Joined} and the data, each as a 32-bit
 * big-endian length and its bytes. Immutable and thread-safe; {@link #toString()} does not show the key.
 */
public final class MessageCodes {
    /** Header of the sender's message counter. */
    public static final String SEQ = "Dtron-Seq";
    /** Header of the sender's wall clock at publishing, ns since the epoch. */
    public static final String TIME = "Dtron-Time";
    /** Header of the message's code, 64 lowercase hexadecimal digits. */
    public static final String MAC = "Dtron-Mac";

    private static final String ALGORITHM = "HmacSHA256";
    private static final byte[] LABEL = "dtron-bus-mac-v1".getBytes(StandardCharsets.UTF_8);
    private static final HexFormat HEX = HexFormat.of();

    private final ThreadLocal<Mac> macs;

    private MessageCodes(byte[] key) {
        SecretKeySpec spec = new SecretKeySpec(key, ALGORITHM);
        this.macs = ThreadLocal.withInitial(() -> mac(spec));
    }

    /**
     * Returns the codes of the key {@code K} (security.md).
     *
     * @throws IllegalArgumentException if the key is empty
     */
    public static MessageCodes forKey(byte[] key) {
        if (Objects.requireNonNull(key, "key").length == 0) {
            throw new IllegalArgumentException("the key of the codes is empty");
        }
        return new MessageCodes(key.clone());
    }

    /**
     * Returns the codes' key {@code K = HMAC-SHA256(secret, "dtron-bus-mac-v1")} of the bus's secret.
     *
     * @throws IllegalArgumentException if the secret is empty
     */
    public static byte[] key(byte[] secret) {
        if (Objects.requireNonNull(secret, "secret").length == 0) {
            throw new IllegalArgumentException("the bus's secret is empty");
        }
        return mac(new SecretKeySpec(secret, ALGORITHM)).doFinal(LABEL);
    }

    /** Returns the codes of the bus's secret: {@code forKey(key(secret))}. */
    public static MessageCodes forSecret(byte[] secret) {
        return forKey(key(secret));
    }

    private static Mac mac(SecretKeySpec key) {
        try {
            Mac mac = Mac.getInstance(ALGORITHM);
            mac.init(key);
            return mac;
        } catch (GeneralSecurityException e) {
            throw new IllegalStateException("this Java has no " + ALGORITHM, e); // every Java SE has it
        }
    }

    /**
     * Returns the code of a message: 64 lowercase hexadecimal digits. A header that is absent is given as null
     * (it counts as empty).
     */
    public String code(String subject, String sender, String seq, String time, String presence, String joined,
            byte[] data) {
        Mac mac = macs.get();
        byte[] length = new byte[4];
        for (String item : new String[] {subject, sender, seq, time, presence, joined}) {
            update(mac, length, item == null ? new byte[0] : item.getBytes(StandardCharsets.UTF_8));
        }
        update(mac, length, data == null ? new byte[0] : data);
        return HEX.formatHex(mac.doFinal());
    }

    private static void update(Mac mac, byte[] length, byte[] item) {
        int n = item.length;
        length[0] = (byte) (n >>> 24);
        length[1] = (byte) (n >>> 16);
        length[2] = (byte) (n >>> 8);
        length[3] = (byte) n;
        mac.update(length);
        mac.update(item);
    }

    /** Returns whether {@code mac} is the code of the message, compared in constant time; a null mac is not. */
    public boolean matches(String mac, String subject, String sender, String seq, String time, String presence,
            String joined, byte[] data) {
        if (mac == null) {
            return false;
        }
        byte[] expected = code(subject, sender, seq, time, presence, joined, data).getBytes(StandardCharsets.US_ASCII);
        return MessageDigest.isEqual(expected, mac.getBytes(StandardCharsets.US_ASCII));
    }

    /** Returns a fresh check of received messages, with no message accepted yet. */
    public Check check() {
        return new Check(this);
    }

    @Override
    public String toString() {
        return "MessageCodes[HMAC-SHA256]";
    }

    /**
     * The check of the messages one member receives, in the order it receives them (one thread): unauthenticated,
     * replayed, stale, in this order. It remembers, per sender, the counters it accepted within
     * {@value #WINDOW} of the highest.
     */
    public static final class Check {
        /** How many counters below a sender's highest accepted one are remembered; any lower is replayed. */
        public static final int WINDOW = 4096;
        /** How far a sender's time may be from the time the stream stored its message. */
        public static final long MAX_SKEW_NANOS = 120_000_000_000L;

        private final MessageCodes codes;
        private final Map<String, Window> windows = new HashMap<>();

        private Check(MessageCodes codes) {
            this.codes = codes;
        }

        /**
         * Checks a received message and, when it passes, takes note of its counter.
         *
         * @param storedNanos when the stream stored the message, ns since the epoch
         * @return why the message is dropped, or null when it passes
         */
        public DropReason check(String subject, String sender, String seq, String time, String presence,
                String joined, byte[] data, String mac, long storedNanos) {
            if (!codes.matches(mac, subject, sender, seq, time, presence, joined, data)) {
                return DropReason.UNAUTHENTICATED;
            }
            long counter = number(seq);
            Window window = windows.get(sender == null ? "" : sender);
            if (counter < 1 || window != null && window.holds(counter)) {
                return DropReason.REPLAYED;
            }
            long sent = number(time);
            if (sent < 0 || Math.abs(sent - storedNanos) > MAX_SKEW_NANOS) {
                return DropReason.STALE;
            }
            windows.computeIfAbsent(sender == null ? "" : sender, s -> new Window()).add(counter);
            return null;
        }

        /**
         * Takes note of the counter of a message published before this member joined, so that a copy of it
         * published again later is replayed; only a message whose code is valid counts, whatever its time.
         *
         * @return whether the message's code is valid and its counter a number
         */
        public boolean learn(String subject, String sender, String seq, String time, String presence, String joined,
                byte[] data, String mac) {
            long counter = number(seq);
            if (counter < 1 || !codes.matches(mac, subject, sender, seq, time, presence, joined, data)) {
                return false;
            }
            Window window = windows.computeIfAbsent(sender == null ? "" : sender, s -> new Window());
            if (!window.holds(counter)) {
                window.add(counter);
            }
            return true;
        }

        /** A header's decimal number (1 to 19 digits, no sign), or -1 when it is none. */
        private static long number(String text) {
            if (text == null || text.isEmpty() || text.length() > 19) {
                return -1;
            }
            for (int i = 0; i < text.length(); i++) {
                if (text.charAt(i) < '0' || text.charAt(i) > '9') {
                    return -1;
                }
            }
            try {
                return Long.parseLong(text);
            } catch (NumberFormatException e) {
                return -1; // beyond a long
            }
        }
    }

    /** The counters accepted from one sender: the highest, and which of the {@value Check#WINDOW} below it. */
    static final class Window {
        private final long[] bits = new long[Check.WINDOW / 64];
        private long highest;

        /** Whether the counter was accepted already, or is too low to tell (and so taken as replayed). */
        boolean holds(long counter) {
            if (counter > highest) {
                return false;
            }
            if (counter <= highest - Check.WINDOW) {
                return true;
            }
            int bit = (int) (counter % Check.WINDOW);
            return (bits[bit >>> 6] & (1L << bit)) != 0;
        }

        /** Notes an accepted counter, which {@link #holds} did not. */
        void add(long counter) {
            if (counter > highest) {
                if (counter - highest >= Check.WINDOW) {
                    java.util.Arrays.fill(bits, 0);
                } else {
                    for (long c = highest + 1; c < counter; c++) {
                        int bit = (int) (c % Check.WINDOW);
                        bits[bit >>> 6] &= ~(1L << bit);
                    }
                }
                highest = counter;
            }
            int bit = (int) (counter % Check.WINDOW);
            bits[bit >>> 6] |= 1L << bit;
        }
    }
}
