package io.dtron.bus.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.attribute.PosixFilePermissions;
import java.util.ArrayList;
import java.util.HexFormat;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.concurrent.Callable;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.Future;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/** The bus's secret: where it comes from, how the default key file is made, which key files are refused. */
class BusKeysTest {
    @TempDir
    Path dir;

    @Test
    void theDefaultDirectoryIsDtronHomeElseDotDtronInTheUsersHome() {
        assertEquals(Path.of("/srv/dtron"), BusKeys.defaultDirectory(Map.of("DTRON_HOME", "/srv/dtron"), "/home/u"));
        assertEquals(Path.of("/home/u/.dtron"), BusKeys.defaultDirectory(Map.of(), "/home/u"));
        assertEquals(Path.of("/home/u/.dtron"), BusKeys.defaultDirectory(Map.of("DTRON_HOME", " "), "/home/u"));
    }

    @Test
    void theFirstMemberMakesTheKeyFileOwnerOnlyWith64HexDigits() throws Exception {
        Path file = dir.resolve("home/bus.key");
        String secret = BusKeys.readOrCreate(file);
        assertTrue(secret.matches("[0-9a-f]{64}"), secret);
        assertEquals(secret + "\n", Files.readString(file));
        assertEquals("rw-------", PosixFilePermissions.toString(Files.getPosixFilePermissions(file)));
        assertEquals("rwx------", PosixFilePermissions.toString(Files.getPosixFilePermissions(file.getParent())));
        assertEquals(List.of(file), Files.list(file.getParent()).toList(), "no temporary file is left");
        assertEquals(secret, BusKeys.readOrCreate(file), "later members read it");
    }

    @Test
    void membersRacingToMakeTheKeyFileAllUseTheOneThatWon() throws Exception {
        Path file = dir.resolve("race/bus.key");
        ExecutorService pool = Executors.newFixedThreadPool(8);
        try {
            List<Future<String>> secrets = new ArrayList<>();
            for (int i = 0; i < 8; i++) {
                secrets.add(pool.submit((Callable<String>) () -> BusKeys.readOrCreate(file)));
            }
            List<String> used = new ArrayList<>();
            for (Future<String> secret : secrets) {
                used.add(secret.get());
            }
            // read once every member is done: before, the file may not be there yet
            String won = Files.readString(file).strip();
            assertEquals(List.of(won, won, won, won, won, won, won, won), used);
        } finally {
            pool.shutdownNow();
        }
    }

    @Test
    void aKeyFileOthersMayReadIsRefusedNamingTheFix() throws Exception {
        Path file = Files.writeString(dir.resolve("shared.key"), "s3cret\n");
        Files.setPosixFilePermissions(file, PosixFilePermissions.fromString("rw-r--r--"));
        BusKeys.KeyFileException e = assertThrows(BusKeys.KeyFileException.class, () -> BusKeys.read(file));
        assertEquals("the bus's key file " + file + " may be read or written by others than its owner (rw-r--r--):"
                + " chmod 600 " + file, e.getMessage());
        Files.setPosixFilePermissions(file, PosixFilePermissions.fromString("rw-------"));
        assertEquals("s3cret", BusKeys.read(file), "white space around the secret is not part of it");
    }

    @Test
    void emptyMissingAndHugeKeyFilesAreRefusedAndAGivenOneIsNeverMade() throws Exception {
        Path empty = Files.writeString(dir.resolve("empty.key"), " \n");
        Files.setPosixFilePermissions(empty, PosixFilePermissions.fromString("rw-------"));
        assertTrue(assertThrows(BusKeys.KeyFileException.class, () -> BusKeys.read(empty)).getMessage()
                .startsWith("the bus's key file " + empty + " is empty"));
        Path missing = dir.resolve("missing.key");
        BusKeys.KeyFileException e = assertThrows(BusKeys.KeyFileException.class,
                () -> BusKeys.secret(Optional.empty(), Optional.of(missing)));
        assertTrue(e.getMessage().startsWith("the bus's key file " + missing + " does not exist"), e.getMessage());
        assertFalse(Files.exists(missing));
        Path huge = Files.write(dir.resolve("huge.key"), new byte[BusKeys.MAX_KEY_FILE + 1]);
        Files.setPosixFilePermissions(huge, PosixFilePermissions.fromString("rw-------"));
        assertTrue(assertThrows(BusKeys.KeyFileException.class, () -> BusKeys.read(huge)).getMessage()
                .contains("is larger than"));
        assertFalse(assertThrows(BusKeys.KeyFileException.class, () -> BusKeys.read(huge)).getMessage()
                .contains("\n"), "one line");
    }

    @Test
    void aSecretGivenWinsOverKeyFiles() {
        assertEquals("s3cret", BusKeys.secret(Optional.of("s3cret"), Optional.of(dir.resolve("missing.key"))));
    }

    @Test
    void theCodeKeyIsTheHmacOfTheLabelUnderTheSecret() {
        // the same figure as Python's hmac.new(b"s3cret", b"dtron-bus-mac-v1", hashlib.sha256).hexdigest()
        assertEquals("aa73ff863bead8e2b8193c159e1bfc47ba4573cbe622241fa4a246dbfdb72819",
                HexFormat.of().formatHex(BusKeys.macKey("s3cret")));
        assertEquals(32, BusKeys.macKey(new String(new byte[] {(byte) 0xC3, (byte) 0xA9}, StandardCharsets.UTF_8))
                .length);
    }
}
