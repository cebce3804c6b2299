package io.dtron.bus.internal;

import java.io.IOException;
import java.io.InputStream;
import java.nio.charset.StandardCharsets;
import java.nio.file.FileAlreadyExistsException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.attribute.FileAttribute;
import java.nio.file.attribute.PosixFilePermission;
import java.nio.file.attribute.PosixFilePermissions;
import java.security.SecureRandom;
import java.util.EnumSet;
import java.util.HexFormat;
import java.util.Map;
import java.util.Optional;
import java.util.Set;

/**
 * Not API. The bus's secret and the key of its message codes ({@code src/site/markdown/security.md}): the secret
 * given, else the content of a key file given, else of the default key file {@code $DTRON_HOME/bus.key} or
 * {@code ~/.dtron/bus.key}, which the first member that needs it creates (directory {@code 0700}, file {@code 0600},
 * 64 hexadecimal digits from {@link SecureRandom} and a newline; written to a temporary file of the same directory
 * and linked to its name, so that of two members racing both use the file that won). A given key file is never
 * created. A key file that is empty, larger than {@value #MAX_KEY_FILE} bytes, or that group or others may read or
 * write, is refused with a one-line {@link KeyFileException}.
 */
public final class BusKeys {
    /** The environment variable naming the directory of the default key file. */
    public static final String DTRON_HOME = "DTRON_HOME";
    /** The default key file's name in its directory. */
    public static final String KEY_FILE_NAME = "bus.key";
    /**
     * The secret of insecure JGroups members: public, so their codes prove nothing, but a secure member (whose key
     * differs) drops their messages and they drop a secure member's.
     */
    static final String INSECURE_SECRET = "dtron-insecure-bus";
    /** The largest key file read, in bytes. */
    static final int MAX_KEY_FILE = 4096;

    private static final Set<PosixFilePermission> SHARED = EnumSet.of(PosixFilePermission.GROUP_READ,
            PosixFilePermission.GROUP_WRITE, PosixFilePermission.OTHERS_READ, PosixFilePermission.OTHERS_WRITE);

    private BusKeys() {
    }

    /** A key file that cannot be used; the message is one line naming the file and what to do. */
    public static final class KeyFileException extends IllegalArgumentException {
        private static final long serialVersionUID = 1L;

        KeyFileException(String message) {
            super(message);
        }
    }

    /**
     * Returns the bus's secret: {@code secret} if given, else the content of {@code keyFile} if given, else of the
     * default key file in the directory {@link #defaultDirectory} names, created if missing.
     *
     * @throws KeyFileException if the key file cannot be read, created or used
     */
    public static String secret(Optional<String> secret, Optional<Path> keyFile) {
        if (secret.isPresent()) {
            return secret.get();
        }
        if (keyFile.isPresent()) {
            return read(keyFile.get());
        }
        Path file = defaultDirectory(System.getenv(), System.getProperty("user.home")).resolve(KEY_FILE_NAME);
        return readOrCreate(file);
    }

    /** The directory of the default key file: {@code $DTRON_HOME} when set and not blank, else {@code HOME/.dtron}. */
    static Path defaultDirectory(Map<String, String> environment, String userHome) {
        String home = environment.get(DTRON_HOME);
        if (home != null && !home.isBlank()) {
            return Path.of(home);
        }
        return Path.of(userHome, ".dtron");
    }

    /** Reads the key file, creating it (and its directory) first if it is missing. */
    static String readOrCreate(Path file) {
        if (!Files.exists(file)) {
            create(file);
        }
        return read(file);
    }

    private static void create(Path file) {
        Path directory = file.toAbsolutePath().getParent();
        boolean posix = directory.getFileSystem().supportedFileAttributeViews().contains("posix");
        try {
            if (!Files.isDirectory(directory)) {
                if (posix) {
                    Files.createDirectories(directory, attribute("rwx------"));
                } else {
                    Files.createDirectories(directory);
                }
            }
            Path temporary = posix ? Files.createTempFile(directory, ".bus.key.", ".tmp", attribute("rw-------"))
                    : Files.createTempFile(directory, ".bus.key.", ".tmp");
            try {
                byte[] random = new byte[32];
                new SecureRandom().nextBytes(random);
                Files.writeString(temporary, HexFormat.of().formatHex(random) + "\n", StandardCharsets.US_ASCII);
                Files.createLink(file, temporary);
            } catch (FileAlreadyExistsException e) {
                // another member created it first: both use that one
            } finally {
                Files.deleteIfExists(temporary);
            }
        } catch (IOException | UnsupportedOperationException e) {
            throw new KeyFileException("cannot create the bus's key file " + file + ": " + e.getMessage()
                    + " (give a key file, or set " + DTRON_HOME + " to a directory of your own)");
        }
    }

    private static FileAttribute<Set<PosixFilePermission>> attribute(String permissions) {
        return PosixFilePermissions.asFileAttribute(PosixFilePermissions.fromString(permissions));
    }

    /** Reads a key file: its content without surrounding white space. */
    static String read(Path file) {
        if (!Files.isRegularFile(file)) {
            throw new KeyFileException("the bus's key file " + file + " does not exist (copy the key file of the"
                    + " bus's other members there, with mode 600)");
        }
        try {
            if (file.getFileSystem().supportedFileAttributeViews().contains("posix")) {
                Set<PosixFilePermission> permissions = Files.getPosixFilePermissions(file);
                if (permissions.stream().anyMatch(SHARED::contains)) {
                    throw new KeyFileException("the bus's key file " + file + " may be read or written by others"
                            + " than its owner (" + PosixFilePermissions.toString(permissions) + "): chmod 600 "
                            + file);
                }
            }
            byte[] content;
            try (InputStream in = Files.newInputStream(file)) {
                content = in.readNBytes(MAX_KEY_FILE + 1);
            }
            if (content.length > MAX_KEY_FILE) {
                throw new KeyFileException("the bus's key file " + file + " is larger than " + MAX_KEY_FILE
                        + " bytes: is it a key file?");
            }
            String secret = new String(content, StandardCharsets.UTF_8).strip();
            if (secret.isEmpty()) {
                throw new KeyFileException("the bus's key file " + file + " is empty: delete it to have a new one"
                        + " made, or copy the key file of the bus's other members there (chmod 600 " + file + ")");
            }
            return secret;
        } catch (IOException e) {
            throw new KeyFileException("cannot read the bus's key file " + file + ": " + e.getMessage());
        }
    }

    /** Returns the key of the message codes of a secret (its UTF-8 bytes): {@link MessageCodes#key(byte[])}. */
    public static byte[] macKey(String secret) {
        return MessageCodes.key(secret.getBytes(StandardCharsets.UTF_8));
    }
}
