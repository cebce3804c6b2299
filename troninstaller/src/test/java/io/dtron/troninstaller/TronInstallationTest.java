package io.dtron.troninstaller;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.attribute.PosixFilePermissions;
import java.util.Map;
import java.util.Optional;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

@Timeout(value = 30, unit = TimeUnit.SECONDS, threadMode = Timeout.ThreadMode.SEPARATE_THREAD)
class TronInstallationTest {
    private static final String LINUX = "Linux";

    @TempDir
    Path dir;

    /** A shell script called {@code name} in {@code folder} that prints {@code text}. */
    private Path script(Path folder, String name, String text, boolean executable) throws IOException {
        Files.createDirectories(folder);
        Path file = folder.resolve(name);
        Files.writeString(file, "#!/bin/sh\necho '" + text + "'\n");
        Files.setPosixFilePermissions(file, PosixFilePermissions.fromString(executable ? "rwxr-xr-x" : "rw-r--r--"));
        return file;
    }

    @Test
    void tronHomeBinWinsOverPath() throws IOException {
        Path home = dir.resolve("tron-1.5");
        Path inHome = script(home.resolve("bin"), "tron", "Uppaal TRON 1.5", true);
        Path onPath = script(dir.resolve("usr-bin"), "tron", "Uppaal TRON 1.4", true);
        TronInstallation installation = new TronInstallation(Map.of("TRON_HOME", home.toString(),
                "PATH", onPath.getParent().toString()), LINUX);
        assertEquals(Optional.of(inHome), installation.find());
    }

    @Test
    void tronHomeItselfIsTriedAfterItsBinFolder() throws IOException {
        Path home = dir.resolve("tron");
        Path direct = script(home, "tron", "TRON", true);
        TronInstallation installation = new TronInstallation(Map.of("TRON_HOME", home.toString()), LINUX);
        assertEquals(Optional.of(direct), installation.find());
        Path inBin = script(home.resolve("bin"), "tron", "TRON", true);
        assertEquals(Optional.of(inBin), installation.find());
    }

    @Test
    void pathFoldersAreSearchedInOrderAndNonExecutablesSkipped() throws IOException {
        Path first = dir.resolve("a");
        Path second = dir.resolve("b");
        Path third = dir.resolve("c");
        Files.createDirectories(first);
        script(second, "tron", "not executable", false);
        Path expected = script(third, "tron", "TRON", true);
        script(dir.resolve("d"), "tron", "later", true);
        String path = first + ":" + second + ":" + third + ":" + dir.resolve("d");
        TronInstallation installation = new TronInstallation(Map.of("PATH", path), LINUX);
        assertEquals(Optional.of(expected), installation.find());
    }

    @Test
    void aTronHomeWithoutTronFallsBackToPath() throws IOException {
        Path onPath = script(dir.resolve("bin"), "tron", "TRON", true);
        TronInstallation installation = new TronInstallation(Map.of("TRON_HOME", dir.resolve("empty").toString(),
                "PATH", onPath.getParent().toString()), LINUX);
        assertEquals(Optional.of(onPath), installation.find());
    }

    @Test
    void windowsLooksForTronExeWithSemicolonPathsAndAnyCaseOfTheVariables() throws IOException {
        Path linuxName = script(dir.resolve("x"), "tron", "TRON", true);
        Path windowsName = script(dir.resolve("y"), "tron.exe", "TRON", false);
        TronInstallation installation = new TronInstallation(Map.of("Path", linuxName.getParent() + ";"
                + windowsName.getParent()), "Windows 11");
        assertEquals("tron.exe", installation.executableName());
        assertEquals(Optional.of(windowsName), installation.find());
        TronInstallation home = new TronInstallation(Map.of("Tron_Home", windowsName.getParent().toString()),
                "Windows 10");
        assertEquals(Optional.of(windowsName), home.find());
    }

    @Test
    void macOsUsesThePlainName() {
        assertEquals("tron", new TronInstallation(Map.of(), "Mac OS X").executableName());
    }

    @Test
    void missingTronGivesAClearMessage() throws IOException {
        Files.createDirectories(dir.resolve("empty"));
        TronInstallation installation = new TronInstallation(Map.of("PATH", dir.resolve("empty").toString()), LINUX);
        assertTrue(installation.find().isEmpty());
        TronNotFoundException e = assertThrows(TronNotFoundException.class, installation::require);
        String message = e.getMessage();
        assertTrue(message.contains("no executable 'tron'"), message);
        assertTrue(message.contains("TRON_HOME is not set"), message);
        assertTrue(message.contains("licence forbids redistribution"), message);
        assertTrue(message.contains("set TRON_HOME to the folder that holds bin/tron"), message);
        assertTrue(message.contains("leave out --backend tron"), message);
        TronNotFoundException withHome = assertThrows(TronNotFoundException.class, () -> new TronInstallation(
                Map.of("TRON_HOME", "/opt/nowhere"), LINUX).require());
        assertTrue(withHome.getMessage().contains("looked in /opt/nowhere/bin and /opt/nowhere (TRON_HOME)"),
                withHome.getMessage());
        assertThrows(TronNotFoundException.class, installation::version);
    }

    @Test
    void versionIsReadFromTheHelpText() throws IOException, TronNotFoundException {
        Path home = dir.resolve("home");
        script(home.resolve("bin"), "tron", "UPPAAL TRON 1.5-beta 2 (c) Aalborg; usage: tron [options] model", true);
        assertEquals("1.5-beta 2", new TronInstallation(Map.of("TRON_HOME", home.toString()), LINUX).version());
    }

    @Test
    void versionParsingFindsTheFirstVersionOnATronOrVersionLine() {
        assertEquals(Optional.of("1.4 Beta 1"), TronInstallation.parseVersion("Uppaal TRON 1.4 Beta 1\n"));
        assertEquals(Optional.of("1.5"), TronInstallation.parseVersion("usage 2.0\nversion: 1.5\n"));
        assertTrue(TronInstallation.parseVersion("usage: something 2.0\n").isEmpty());
    }

    @Test
    void anExecutableWithoutAVersionIsAnError() throws IOException {
        Path fake = script(dir.resolve("bin"), "tron", "hello", true);
        IOException e = assertThrows(IOException.class, () -> TronInstallation.version(fake));
        assertTrue(e.getMessage().contains("printed no version: 'hello'"), e.getMessage());
        assertFalse(e.getMessage().isBlank());
    }
}
